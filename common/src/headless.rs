//! The headless runner: renders every variant offscreen, compares it with
//! the exact reference, times it, and writes the outputs of INTERFACES.md.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::baseline::Baseline;
use crate::cli::Args;
use crate::gpu::Gpu;
use crate::lesson::{variant_name, Lesson};
use crate::metrics;
use crate::reference::try_render_reference;
use crate::render::SceneGpu;
use crate::report::{combine, AdapterReport, BaselineReport, Report, VariantReport};
use crate::scene::Scene;
use crate::timing::{median_times, samples, spread_times, FrameTimes, Timer};

/// What a headless run wrote: the report, and the folder it wrote into.
pub struct HeadlessRun {
    pub report: Report,
    pub out_dir: PathBuf,
}

const WARM_UP_FRAMES: u32 = 2;

// ANCHOR: run_headless
/// Renders every variant offscreen, compares it with the exact reference,
/// times it, and writes the outputs of INTERFACES.md to the output folder.
pub fn run_headless<L: Lesson>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<HeadlessRun> {
    let out_dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(L::NAME));
    std::fs::create_dir_all(&out_dir)
        .with_context(|| format!("--out: cannot create {}", out_dir.display()))?;
    let gpu = Gpu::new(args.backend.as_deref(), args.adapter.as_deref(), None)?;
    let scene_name = scene.name.clone();
    let sg = SceneGpu::new(&gpu, scene, args.width, args.height)?;
    let targets = sg.frame_targets(&gpu);
    let mut lesson = L::new(&gpu, &sg)?;
    let mut timer = Timer::new(&gpu);

    let reference = try_render_reference(&sg.scene, sg.camera.view_proj, args.width, args.height)?;
    let (w, h) = (args.width, args.height);
    for k in 0..sg.scene.lights.len() {
        save(
            &metrics::reference_visibility_image(&reference, k),
            &out_dir.join(format!("reference_visibility_l{k}.png")),
        )?;
    }

    let mut rows = Vec::new();
    for &variant in variants {
        let v = variant_name(variant);
        if let Some(why) = lesson.unavailable(variant) {
            if !args.variants.is_empty() {
                anyhow::bail!("{why}");
            }
            eprintln!("note: {}: skipped {why}", L::NAME);
            continue;
        }
        let times = timed_frames(&mut timer, &gpu, args.frames, |frame| {
            lesson.render(frame, &sg, &targets, variant)
        })?;
        let images = targets.read(&gpu)?;
        let color = image::RgbaImage::from_raw(w, h, images.color.clone())
            .context("colour readback size")?;
        save(&color, &out_dir.join(format!("{v}.png")))?;
        let mut per_light = Vec::new();
        for k in 0..sg.scene.lights.len() {
            let vis = &images.visibility[k];
            let cmp = metrics::compare(&reference, k, &images.id, vis);
            save(
                &metrics::visibility_image(&images.id, vis, w, h),
                &out_dir.join(format!("{v}_visibility_l{k}.png")),
            )?;
            save(&cmp.diff, &out_dir.join(format!("{v}_diff_l{k}.png")))?;
            per_light.push(cmp.stats);
        }
        lesson.write_extras(&gpu, &sg, variant, &out_dir)?;
        rows.push(VariantReport {
            name: v,
            error: combine(&per_light),
            error_per_light: per_light,
            timing_ms: median_times(&times),
            timing_spread_ms: spread_times(&times),
            timing_samples_ms: samples(&times),
            timing_source: timer.source(),
            counters: lesson.counters(variant),
        });
    }
    if rows.is_empty() {
        anyhow::bail!("{}: this adapter can render none of the variants", L::NAME);
    }
    // The no-shadow baseline, timed like the variants, after them (its
    // images are not kept: the targets hold the last variant's frame
    // until here).
    let baseline = Baseline::new(&gpu, &sg);
    let times = timed_frames(&mut timer, &gpu, args.frames, |frame| {
        baseline.render(frame, &sg, &targets)
    })?;
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
        baseline: Some(BaselineReport {
            timing_ms: median_times(&times),
            timing_spread_ms: spread_times(&times),
            timing_samples_ms: samples(&times),
        }),
    };
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(out_dir.join("report.json"), json)
        .with_context(|| format!("cannot write {}", out_dir.join("report.json").display()))?;
    Ok(HeadlessRun { report, out_dir })
}
// ANCHOR_END: run_headless

// ANCHOR: timed_frames
/// Renders [`WARM_UP_FRAMES`] untimed frames, then `frames` timed ones.
fn timed_frames(
    timer: &mut Timer,
    gpu: &Gpu,
    frames: u32,
    mut render: impl FnMut(&mut crate::timing::Frame) -> Result<()>,
) -> Result<Vec<FrameTimes>> {
    let mut times = Vec::new();
    for i in 0..WARM_UP_FRAMES + frames {
        let mut frame = timer.frame(gpu);
        render(&mut frame)?;
        let t = frame.finish()?;
        if i >= WARM_UP_FRAMES {
            times.push(t);
        }
    }
    Ok(times)
}
// ANCHOR_END: timed_frames

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
