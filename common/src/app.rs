//! Running a lesson: the [`Lesson`] trait, the headless runner that writes
//! the outputs of INTERFACES.md, and the interactive window. Both runners
//! call the same `Lesson::render`, which draws into any [`FrameTargets`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Parser;

use crate::cli::Args;
use crate::gpu::Gpu;
use crate::metrics;
use crate::reference::{render_reference, Reference};
use crate::render::{FrameImages, FrameTargets, SceneGpu};
use crate::report::{combine, AdapterReport, Report, VariantReport};
use crate::scene::Scene;
use crate::timing::{median_times, Frame, Timer};

/// What a lesson provides. The runners do the rest.
pub trait Lesson: Sized {
    /// `"lesson_01"`.
    const NAME: &'static str;
    /// The default scene, as TOML text (built-in meshes only).
    const DEFAULT_SCENE: &'static str;

    /// Every variant's name, in report order.
    fn variants() -> Vec<String>;

    /// Rejects scenes the lesson cannot render (one clear line).
    fn check_scene(_scene: &Scene) -> Result<()> {
        Ok(())
    }

    /// Creates the lesson's pipelines and resources.
    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self>;

    /// Records one frame of `variant` into `targets`, one named pass at a time.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: &str,
    ) -> Result<()>;

    /// Counters for the report (casters drawn, fragments, ...), after `render`.
    fn counters(&self, _variant: &str) -> BTreeMap<String, u64> {
        BTreeMap::new()
    }

    /// Extra debug images (the depth map, ...), written after the last frame.
    fn write_extras(
        &self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        _variant: &str,
        _out: &Path,
    ) -> Result<()> {
        Ok(())
    }
}

/// A lesson's `main`: parse the command line, run, and turn any error into
/// one line on stderr and a non-zero exit code.
pub fn main<L: Lesson>() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            let msg = e.to_string();
            eprintln!(
                "{}",
                msg.lines().next().unwrap_or("error: bad command line")
            );
            return ExitCode::from(2);
        }
    };
    match run::<L>(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let msg = format!("{e:#}").replace('\n', " ");
            eprintln!("error: {}: {msg}", L::NAME);
            ExitCode::FAILURE
        }
    }
}

fn display_available() -> bool {
    std::env::var_os("DISPLAY").is_some_and(|v| !v.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|v| !v.is_empty())
}

/// Runs as the command line says: list variants, headless, or the window.
pub fn run<L: Lesson>(args: &Args) -> Result<()> {
    if args.list_variants {
        for v in L::variants() {
            println!("{v}");
        }
        return Ok(());
    }
    let variants = select_variants::<L>(&args.variants)?;
    let scene = load_scene::<L>(args)?;
    if args.headless || !display_available() {
        let result = run_headless::<L>(args, scene, &variants)?;
        print!("{}", result.report.table());
        println!("outputs: {}", result.out_dir.display());
        Ok(())
    } else {
        crate::window::run_window::<L>(args, scene, variants)
    }
}

/// The variants asked for, checked against the lesson's list.
pub fn select_variants<L: Lesson>(asked: &[String]) -> Result<Vec<String>> {
    let all = L::variants();
    if asked.is_empty() {
        return Ok(all);
    }
    for a in asked {
        if !all.contains(a) {
            bail!(
                "--variant: unknown variant {a:?} (known: {})",
                all.join(", ")
            );
        }
    }
    Ok(asked.to_vec())
}

/// The `--scene` file, or the lesson's default scene.
pub fn load_scene<L: Lesson>(args: &Args) -> Result<Scene> {
    let scene = match &args.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::builtin(&format!("{} default scene", L::NAME), L::DEFAULT_SCENE)?,
    };
    L::check_scene(&scene)?;
    Ok(scene)
}

/// One variant's results, for tests.
pub struct VariantRun {
    pub name: String,
    pub images: FrameImages,
    /// A coarse text rendering of each light's visibility (for snapshots).
    pub ascii: Vec<String>,
}

pub struct HeadlessRun {
    pub report: Report,
    pub reference: Reference,
    pub variants: Vec<VariantRun>,
    pub out_dir: PathBuf,
}

const WARM_UP_FRAMES: u32 = 2;

// ANCHOR: run_headless
/// Renders every variant offscreen, compares it with the exact reference,
/// times it, and writes the outputs of INTERFACES.md to the output folder.
pub fn run_headless<L: Lesson>(
    args: &Args,
    scene: Scene,
    variants: &[String],
) -> Result<HeadlessRun> {
    let out_dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(L::NAME));
    std::fs::create_dir_all(&out_dir)
        .with_context(|| format!("--out: cannot create {}", out_dir.display()))?;
    let gpu = Gpu::new(args.backend.as_deref(), None)?;
    let scene_name = scene.name.clone();
    let sg = SceneGpu::new(&gpu, scene, args.width, args.height)?;
    let targets = FrameTargets::new(&gpu, &sg);
    let mut lesson = L::new(&gpu, &sg)?;
    let mut timer = Timer::new(&gpu);

    let reference = render_reference(&sg.scene, sg.camera.view_proj, args.width, args.height);
    let (w, h) = (args.width, args.height);
    for k in 0..sg.scene.lights.len() {
        save(
            &metrics::reference_visibility_image(&reference, k),
            &out_dir.join(format!("reference_visibility_l{k}.png")),
        )?;
    }

    let mut rows = Vec::new();
    let mut runs = Vec::new();
    for v in variants {
        let mut times = Vec::new();
        for i in 0..WARM_UP_FRAMES + args.frames {
            let mut frame = timer.frame(&gpu);
            lesson.render(&mut frame, &sg, &targets, v)?;
            let t = frame.finish()?;
            if i >= WARM_UP_FRAMES {
                times.push(t);
            }
        }
        let images = targets.read(&gpu)?;
        let color = image::RgbaImage::from_raw(w, h, images.color.clone())
            .context("colour readback size")?;
        save(&color, &out_dir.join(format!("{v}.png")))?;
        let mut per_light = Vec::new();
        let mut ascii = Vec::new();
        for k in 0..sg.scene.lights.len() {
            let vis = &images.visibility[k];
            let cmp = metrics::compare(&reference, k, &images.id, vis);
            save(
                &metrics::visibility_image(&images.id, vis, w, h),
                &out_dir.join(format!("{v}_visibility_l{k}.png")),
            )?;
            save(&cmp.diff, &out_dir.join(format!("{v}_diff_l{k}.png")))?;
            per_light.push(cmp.stats);
            ascii.push(metrics::ascii_mask(&images.id, vis, w, h, 64, 24));
        }
        lesson.write_extras(&gpu, &sg, v, &out_dir)?;
        rows.push(VariantReport {
            name: v.clone(),
            error: combine(&per_light),
            error_per_light: per_light,
            timing_ms: median_times(&times),
            timing_source: timer.source(),
            counters: lesson.counters(v),
        });
        runs.push(VariantRun {
            name: v.clone(),
            images,
            ascii,
        });
    }
    let report = Report {
        lesson: L::NAME.to_string(),
        adapter: AdapterReport {
            name: gpu.adapter_name(),
            backend: gpu.backend_name(),
        },
        width: w,
        height: h,
        scene: scene_name,
        reference_ms: reference.ms,
        frames: args.frames,
        variants: rows,
    };
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(out_dir.join("report.json"), json)
        .with_context(|| format!("cannot write {}", out_dir.join("report.json").display()))?;
    Ok(HeadlessRun {
        report,
        reference,
        variants: runs,
        out_dir,
    })
}
// ANCHOR_END: run_headless

/// Saves an image, naming the file on failure.
pub fn save<P, C>(img: &image::ImageBuffer<P, C>, path: &Path) -> Result<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}
