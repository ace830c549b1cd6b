//! The headless runner: renders every variant offscreen, compares it with
//! the exact reference, times it, and writes the outputs the book's
//! appendix "Interfaces" lists (`book/src/appendix/interfaces.md`).

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::gpu::depth_probe::DepthStorage;
use crate::gpu::render::SceneGpu;
use crate::gpu::targets::{FrameImages, FrameTargets};
use crate::gpu::Gpu;
use crate::measure::baseline::Baseline;
use crate::measure::protocol::{block_order, time_blocks, verdicts, Verdicts, WarmUp};
use crate::measure::report::VariantReport;
use crate::measure::report::{combine, AdapterReport, BaselineReport, CameraPathReport, Report};
use crate::measure::timing::{median_times, samples, spread_times, Timer};
use crate::reference::metrics::{self, pixel_states, PixelState, ReferenceStates};
use crate::reference::{cache, dv_view};
use crate::run::cli::Args;
use crate::run::files::{save, write_json};
use crate::run::jittered;
use crate::run::lesson::{apply_cli_knobs, knob_values};
use crate::run::lesson::{variant_name, Lesson};
use crate::scene::camera_path::{check_path, path_cameras, CameraPath, Shimmer};
use crate::scene::Scene;

/// What a headless run wrote: the report, and the folder it wrote into.
pub struct HeadlessRun {
    pub report: Report,
    pub out_dir: PathBuf,
}

/// A headless run's GPU, scene, lesson, and the variants it can render,
/// set up as the command line says ([`setup`]).
pub(crate) struct Setup<L: Lesson> {
    pub out_dir: PathBuf,
    pub gpu: Gpu,
    pub sg: SceneGpu,
    pub targets: FrameTargets,
    pub lesson: L,
    pub timer: Timer,
    pub runnable: Vec<L::Variant>,
    pub adapter: AdapterReport,
    pub scene_name: String,
}

/// Checks the command line against the scene and the lesson, opens the
/// GPU and the output folder, builds the lesson and sets its knobs.
pub(crate) fn setup<L: Lesson>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<Setup<L>> {
    let out_dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(L::NAME));
    std::fs::create_dir_all(&out_dir)
        .with_context(|| format!("--out: cannot create {}", out_dir.display()))?;
    if scene.camera_path.is_some() && !L::CAMERA_PATH {
        anyhow::bail!(
            "scene {}: [camera_path]: {} does not re-fit to a moving camera; lessons 01 and 09 do",
            scene.name,
            L::NAME
        );
    }
    check_path(&scene).map_err(|e| anyhow::anyhow!("scene {}: {e}", scene.name))?;
    let names: Vec<String> = variants.iter().map(|&v| variant_name(v)).collect();
    if let Some(f) = (args.fragile_variants.iter()).find(|f| !names.contains(f)) {
        let names = names.join(", ");
        anyhow::bail!("--fragile-variant: {f:?} is not a variant of this run ({names})");
    }
    let gpu = Gpu::open(
        args.backend.as_deref(),
        args.adapter.as_deref(),
        args.depth_format.as_deref(),
        None,
    )?;
    let scene_name = scene.name.clone();
    let depth = gpu.depth_stencil_format();
    let depth_probe = crate::gpu::depth_probe::probe(&gpu, depth)?;
    if depth_probe.storage == DepthStorage::Unknown {
        eprintln!(
            "warning: {}: cannot tell what {depth:?} stores on {} (depth probe: {depth_probe:?}); report.json says \"unknown\"",
            L::NAME,
            gpu.adapter_name()
        );
    }
    let adapter = AdapterReport {
        name: gpu.adapter_name(),
        backend: gpu.backend_name(),
        depth_format: format!("{depth:?}"),
        depth_storage: depth_probe.storage.name().to_string(),
    };
    let sg = SceneGpu::new(&gpu, scene, args.width, args.height)?;
    let targets = sg.frame_targets(&gpu);
    let mut lesson = L::new(&gpu, &sg)?;
    let timer = Timer::new(&gpu);
    let mut runnable = Vec::new();
    for &variant in variants {
        match lesson.unavailable(variant) {
            Some(why) if !args.variants.is_empty() => anyhow::bail!("{why}"),
            Some(why) => eprintln!("note: {}: skipped {why}", L::NAME),
            None => runnable.push(variant),
        }
    }
    if runnable.is_empty() {
        anyhow::bail!("this adapter can render none of the variants (the notes above say why)");
    }
    apply_cli_knobs(&mut lesson, &gpu, &sg, &runnable, &args.knobs)?;
    Ok(Setup {
        out_dir,
        gpu,
        sg,
        targets,
        lesson,
        timer,
        runnable,
        adapter,
        scene_name,
    })
}

/// Times every variant, back to back and interleaved with the no-shadow
/// baseline, before any CPU-only work lets the GPU idle
/// (measure::protocol).
pub(crate) fn time_variants<L: Lesson>(s: &mut Setup<L>, args: &Args) -> Result<Verdicts> {
    let baseline = Baseline::new(&s.gpu, &s.sg);
    let order = block_order(s.runnable.len());
    let (lesson, sg, targets, runnable) = (&mut s.lesson, &s.sg, &s.targets, &s.runnable);
    let blocks = time_blocks(
        &mut s.timer,
        &s.gpu,
        WarmUp::with_min_ms(args.warm_up_ms),
        args.frames,
        &order,
        |frame, id| match id {
            Some(i) => lesson.render(frame, sg, targets, runnable[i]),
            None => baseline.render(frame, sg, targets),
        },
    )?;
    let names: Vec<String> = runnable.iter().map(|&v| variant_name(v)).collect();
    Ok(verdicts(&blocks, &names, args.warm_up_ms))
}

/// The no-shadow baseline's times, from the timed blocks.
pub(crate) fn baseline_report(t: &Verdicts) -> BaselineReport {
    BaselineReport {
        timing_ms: median_times(&t.baseline.0),
        timing_spread_ms: spread_times(&t.baseline.0),
        timing_samples_ms: samples(&t.baseline.0),
        blocks: t.baseline.1.clone(),
    }
}

// ANCHOR: run_headless
/// Renders every variant offscreen, compares it with the exact reference,
/// times it, and writes the outputs the book's appendix "Interfaces"
/// lists to the output folder.
pub fn run_headless<L: Lesson>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<HeadlessRun> {
    let mut setup = setup::<L>(args, scene, variants)?;
    // 1. Time every variant first (`--no-timing` times nothing: the tests
    //    read no times).
    let timed = match args.no_timing {
        true => None,
        false => Some(time_variants(&mut setup, args)?),
    };
    let Setup {
        out_dir,
        gpu,
        mut sg,
        targets,
        mut lesson,
        mut timer,
        runnable,
        adapter,
        scene_name,
    } = setup;

    // 2. The reference, then each variant's images and error (untimed).
    let reference = cache::reference(&sg.scene, sg.camera.view_proj, args.width, args.height)?;
    check_receivers(&sg, &reference)?;
    let (w, h) = (args.width, args.height);
    let reference_states = ReferenceStates::new(&reference);
    let c = &sg.scene.camera;
    let forward = (c.target - c.eye).normalize().as_vec3();
    let view_depth = metrics::view_depth(&reference, sg.camera.eye, forward);
    // The path's references, one per frame, computed for the first variant.
    let mut path_references = Vec::new();
    for k in 0..sg.scene.lights.len() {
        save(
            &metrics::reference_visibility_image(&reference, k),
            &out_dir.join(format!("reference_visibility_l{k}.png")),
        )?;
    }

    let mut rows = Vec::new();
    for (i, &variant) in runnable.iter().enumerate() {
        let v = variant_name(variant);
        // The targets hold the last block's frame: render this variant's.
        // Its frames up to the one the lesson counts on (the counters go
        // with the images).
        for _ in 0..L::COUNTED_ON_FRAME {
            let mut frame = timer.frame(&gpu);
            lesson.render(&mut frame, &sg, &targets, variant)?;
            frame.finish()?;
        }
        let images = targets.read(&gpu)?;
        let color = image::RgbaImage::from_raw(w, h, images.color.clone())
            .context("colour readback size")?;
        save(&color, &out_dir.join(format!("{v}.png")))?;
        let mut per_light = Vec::new();
        for k in 0..sg.scene.lights.len() {
            let vis = &images.visibility[k];
            // Receivers below their own horizon for part of the emitter: apart.
            let clipped = reference.horizon_clipped.get(k).map(Vec::as_slice);
            let cmp = metrics::compare(&reference, k, &images.id, vis, clipped);
            save(
                &metrics::visibility_image(&images.id, vis, w, h),
                &out_dir.join(format!("{v}_visibility_l{k}.png")),
            )?;
            save(&cmp.diff, &out_dir.join(format!("{v}_diff_l{k}.png")))?;
            // A soft shadow's error is below the diff's V = ½: its signed ΔV.
            if reference.area_light[k] {
                save(
                    &dv_view::dv_image(&reference, k, &images.id, vis),
                    &out_dir.join(format!("{v}_dv_l{k}.png")),
                )?;
            }
            per_light.push(cmp.stats);
        }
        lesson.write_extras(&gpu, &sg, variant, &out_dir)?;
        if let Some(b) = lesson.buffer_view(&gpu, &sg, variant)? {
            save(&b.image, &out_dir.join(format!("{v}_buffer.png")))?;
        }
        let states = light_states(&reference_states, &images);
        let class_map = lesson.pixel_classes(&sg, variant, &view_depth);
        let classes = match &class_map {
            Some((names, class_of)) => Some(metrics::class_errors(names, class_of, &states)?),
            None => None,
        };
        // Counters first: the path's and the jitter's frames may change
        // what a frame counts.
        let counters = lesson.counters(variant);
        let fragile = if args.measures_bounds(&v) {
            let run = jittered::Measured {
                reference: &reference,
                images: &images,
                counters: &counters,
                classes: class_map.as_ref(),
            };
            Some(jittered::fragile_of(
                &gpu,
                &mut sg,
                &targets,
                &mut timer,
                &mut lesson,
                variant,
                run,
            )?)
        } else {
            None
        };
        let camera_path = match sg.scene.camera_path {
            Some(path) => {
                let mut walk = PathWalk {
                    gpu: &gpu,
                    sg: &mut sg,
                    targets: &targets,
                    timer: &mut timer,
                    references: &mut path_references,
                };
                let (report, shimmer) = walk.measure(&mut lesson, variant, &path)?;
                let lights = sg.scene.lights.len();
                save(
                    &shimmer.image(lights),
                    &out_dir.join(format!("{v}_shimmer.png")),
                )?;
                let over = shimmer.image_over(lights, &color);
                save(&over, &out_dir.join(format!("{v}_shimmer_over.png")))?;
                Some(report)
            }
            None => None,
        };
        let no_times = Vec::new();
        let (times, check) = match &timed {
            Some(t) => (&t.variants[i].0, Some(t.variants[i].1.clone())),
            None => (&no_times, None),
        };
        rows.push(VariantReport {
            name: v,
            error: combine(&per_light),
            error_per_light: per_light,
            timing_ms: median_times(times),
            timing_spread_ms: spread_times(times),
            timing_samples_ms: samples(times),
            timing_source: timer.source(),
            counters,
            knobs: knob_values(&lesson, variant),
            camera_path,
            classes,
            timing_check: check,
            fragile,
        });
    }
    let report = Report {
        lesson: L::NAME.to_string(),
        adapter,
        width: w,
        height: h,
        scene: scene_name,
        reference_ms: reference.ms,
        frames: args.frames,
        variants: rows,
        baseline: timed.as_ref().map(baseline_report),
        timing_protocol: timed.map(|t| t.protocol),
    };
    write_json(&report, &out_dir.join("report.json"))?;
    Ok(HeadlessRun { report, out_dir })
}
// ANCHOR_END: run_headless

/// Refuses a view with no receiver: every error figure would be 0.000 %
/// of nothing. Names what the camera sees instead.
fn check_receivers(sg: &SceneGpu, reference: &crate::reference::Reference) -> Result<()> {
    if metrics::reference_receivers(reference) > 0 {
        return Ok(());
    }
    let c = &sg.scene.camera;
    let far = match c.far {
        crate::scene::Far::Finite(f) => format!("{f}"),
        crate::scene::Far::Infinite => "infinite".to_string(),
    };
    let what = if reference.hits.iter().all(Option::is_none) {
        format!(
            "the camera sees no geometry between its near plane ({}) and far plane ({far})",
            c.near
        )
    } else {
        "no surface the camera sees faces a light within the light's reach".to_string()
    };
    anyhow::bail!(
        "scene {}: {what}, so there is no receiver to measure a shadow on: move [camera] (eye, target, near, far) or the lights",
        sg.scene.name
    )
}

/// Every light's [`PixelState`]s of a frame's images.
fn light_states(reference: &ReferenceStates, images: &FrameImages) -> Vec<Vec<PixelState>> {
    let lights = images.visibility.iter();
    let states = lights
        .enumerate()
        .map(|(k, vis)| pixel_states(reference, k, &images.id, vis));
    states.collect()
}

/// What rendering a variant along the scene's camera path needs.
struct PathWalk<'a> {
    gpu: &'a Gpu,
    sg: &'a mut SceneGpu,
    targets: &'a FrameTargets,
    timer: &'a mut Timer,
    /// The reference of each frame so far, and which of its pixels' surfaces
    /// the next frame's view holds: the same for every variant.
    references: &'a mut Vec<(ReferenceStates, Vec<bool>)>,
}

impl PathWalk<'_> {
    /// Renders `variant` at each camera of `path` (untimed), counts its
    /// flips against the reference's, and puts the scene's camera back.
    fn measure<L: Lesson>(
        &mut self,
        lesson: &mut L,
        variant: L::Variant,
        path: &CameraPath,
    ) -> Result<(CameraPathReport, Shimmer)> {
        let base = self.sg.scene.camera.clone();
        let mut shimmer = Shimmer::new(self.sg.width, self.sg.height);
        let cameras = path_cameras(&base, path);
        let walked = (0..cameras.len()).try_for_each(|i| {
            let next = cameras.get(i + 1);
            let states = self.frame_at(&cameras[i], next, i, lesson, variant)?;
            if let Some(next) = next {
                // The probe: this view, the next frame's fit.
                let probe = self.probe(next, i, lesson, variant)?;
                shimmer.add_probe(&states, &probe, &self.references[i].1);
            }
            shimmer.add_frame(states);
            Ok::<(), anyhow::Error>(())
        });
        self.sg.scene.camera = base;
        self.sg.set_camera(self.gpu);
        walked?;
        Ok((shimmer.report(), shimmer))
    }

    /// Path frame `i`, seen from `camera`: every light's pixel states.
    /// The first variant also makes the frame's reference, and marks the
    /// pixels whose surface `next`'s view holds too.
    fn frame_at<L: Lesson>(
        &mut self,
        camera: &crate::scene::Camera,
        next: Option<&crate::scene::Camera>,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        let sg = &mut *self.sg;
        sg.scene.camera = camera.clone();
        sg.set_camera(self.gpu);
        if self.references.len() == i {
            let r = cache::reference(&sg.scene, sg.camera.view_proj, sg.width, sg.height)?;
            let seen = match next {
                Some(next) => {
                    sg.scene.camera = next.clone();
                    let m = crate::scene::camera::camera_matrices(&sg.scene, sg.width, sg.height);
                    sg.scene.camera = camera.clone();
                    in_view(&r, m.view_proj)
                }
                None => Vec::new(),
            };
            self.references.push((ReferenceStates::new(&r), seen));
        }
        self.render_states(i, lesson, variant)
    }

    /// The probe after frame `i`: frame `i`'s view (its matrices stay in
    /// the scene's uniforms), the lesson fitting to `next` (the scene's
    /// camera, which the lessons with `CAMERA_PATH` re-read every frame).
    fn probe<L: Lesson>(
        &mut self,
        next: &crate::scene::Camera,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        self.sg.scene.camera = next.clone();
        self.render_states(i, lesson, variant)
    }

    /// Renders one untimed frame and reads every light's pixel states
    /// against path frame `i`'s reference.
    fn render_states<L: Lesson>(
        &mut self,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        let mut frame = self.timer.frame(self.gpu);
        lesson.render(&mut frame, self.sg, self.targets, variant)?;
        frame.finish()?;
        let images = self.targets.read(self.gpu)?;
        Ok(light_states(&self.references[i].0, &images))
    }
}

/// Per pixel of `r`: its surface projects inside the view of `view_proj`
/// (origin-relative), in front of the eye.
fn in_view(r: &crate::reference::Reference, view_proj: glam::Mat4) -> Vec<bool> {
    r.hits
        .iter()
        .map(|h| {
            h.as_ref().is_some_and(|h| {
                let c = view_proj * h.position.extend(1.0);
                c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w
            })
        })
        .collect()
}
