//! The [`Lesson`] trait: what a lesson provides. The runners (headless in
//! [`crate::run::headless`], interactive in [`crate::run::window`]) do the rest, and
//! both call the same [`Lesson::render`], which draws into any
//! [`FrameTargets`].

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{bail, Result};
use clap::ValueEnum;

use crate::gpu::render::SceneGpu;
use crate::gpu::targets::FrameTargets;
use crate::gpu::Gpu;
use crate::measure::timing::Frame;
use crate::run::knobs::Knob;
use crate::scene::Scene;

/// What a lesson provides. The runners do the rest.
pub trait Lesson: Sized + 'static {
    /// `"lesson_01"`.
    const NAME: &'static str;
    /// The default scene, as TOML text (built-in meshes only).
    const DEFAULT_SCENE: &'static str;
    /// The lesson's variants, in report order. `--variant NAME` and the
    /// report use the names clap's `ValueEnum` gives them.
    type Variant: ValueEnum + Copy + std::fmt::Debug + 'static;

    /// Rejects scenes the lesson cannot render (one clear line).
    fn check_scene(_scene: &Scene) -> Result<()> {
        Ok(())
    }

    /// Whether the lesson renders lights with a size (`radius`,
    /// `angular_radius_deg`): soft shadows, lesson 10. The runner refuses
    /// such a scene with one line for the lessons that keep `false`.
    const AREA_LIGHTS: bool = false;

    /// Whether the lesson re-reads the camera on every [`Lesson::render`], so
    /// that a scene's `[camera_path]` (shimmer, chapter 09) is measured right.
    /// A lesson that caches camera-dependent state keeps `false`, and the
    /// runner refuses such a scene with one line.
    const CAMERA_PATH: bool = false;

    /// Whether the lesson draws a scene's `[camera] shift` (an off-centre
    /// frustum) right. Lessons that draw with the scene's camera matrices
    /// see it for free; one that rebuilds the frustum from `fov_y_deg` and
    /// the aspect alone sets `false`, and the runner refuses a shifted
    /// scene with one line.
    const SUPPORTS_CAMERA_SHIFT: bool = true;

    /// Classes the pixels fall into, for an error breakdown in the report
    /// (lesson 09: the cascade each pixel samples). `view_depth[p]` is the
    /// distance along the camera's forward axis to the surface pixel `p`
    /// sees (the exact reference's hit), NaN where it sees nothing.
    /// Returns the class names and one class index per pixel, or `None`.
    fn pixel_classes(
        &self,
        _scene: &SceneGpu,
        _variant: Self::Variant,
        _view_depth: &[f32],
    ) -> Option<(Vec<String>, Vec<u8>)> {
        None
    }

    /// Creates the lesson's pipelines and resources.
    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self>;

    /// Records one frame of `variant` into `targets`, one named pass at a time.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Self::Variant,
    ) -> Result<()>;

    /// Why this adapter cannot render `variant` (a missing feature, a
    /// backend that loses its precision), or `None`. A default run (no
    /// `--variant`) skips such variants with one note line each; asking for
    /// one by name is an error that prints the reason.
    fn unavailable(&self, _variant: Self::Variant) -> Option<String> {
        None
    }

    /// Counters for the report (casters drawn, fragments, ...), after `render`.
    fn counters(&self, _variant: Self::Variant) -> BTreeMap<String, u64> {
        BTreeMap::new()
    }

    /// The frame of a variant, from its first after another variant's, on
    /// which the lesson has counted it: 1 for a lesson that counts every
    /// frame (the default), 2 for lessons 05–08, which count a variant's
    /// volumes on its second frame against the depth its first left. The
    /// runner draws that many untimed frames before it reads a variant's
    /// images and counters.
    const COUNTED_ON_FRAME: u32 = 1;

    /// Forgets what `variant` counted once (lessons 05–08), so that its
    /// next [`Lesson::COUNTED_ON_FRAME`] frames count again: the runner's
    /// `--fragile` frames, drawn with the camera moved.
    fn count_again(&mut self, _variant: Self::Variant) {}

    /// The knobs `variant` exposes ([`crate::run::knobs`]), with the values
    /// it runs with now: the parameters its chapter discusses. None by
    /// default.
    fn knobs(&self, _variant: Self::Variant) -> Vec<Knob> {
        Vec::new()
    }

    /// Sets a knob of `variant` that [`Lesson::knobs`] lists, to a value in
    /// its range (call [`apply_knob`], which checks both).
    /// The next [`Lesson::render`] of `variant` uses it.
    fn set_knob(
        &mut self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Self::Variant,
        name: &str,
        _value: f64,
    ) -> Result<()> {
        anyhow::bail!("--knob {name}: {} has no knobs", variant_name(variant))
    }

    /// The lesson's own buffer for the window's "buffer" view (lessons
    /// 01–03: the shadow map; 04: the cube map's cross; 05–08: the stencil
    /// count; 09: the cascade each pixel samples), as the last
    /// [`Lesson::render`] of `variant` left it, or `None`.
    fn buffer_view(
        &self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        _variant: Self::Variant,
    ) -> Result<Option<BufferView>> {
        Ok(None)
    }

    /// Extra debug images (the depth map, ...), written after the last frame.
    fn write_extras(
        &self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        _variant: Self::Variant,
        _out: &Path,
    ) -> Result<()> {
        Ok(())
    }
}

/// A lesson's own buffer as an image, for the window's "buffer" view.
pub struct BufferView {
    /// What the image shows, in one line ("shadow map, light 0: depth, near
    /// dark").
    pub title: String,
    pub image: image::RgbaImage,
}

/// A variant's one-line doc comment (its `///` in the lesson), or "".
pub fn variant_doc<V: ValueEnum>(v: V) -> String {
    let help = v
        .to_possible_value()
        .and_then(|p| p.get_help().map(|h| h.to_string()));
    let help = help.unwrap_or_default();
    help.lines().next().unwrap_or("").to_string()
}

/// A variant's name, as `--variant` and the report spell it.
pub fn variant_name<V: ValueEnum>(v: V) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// The prefix of an exercise's variant name (`exercise_slope_bias`): the
/// student's code from the chapter's exercises, run only when asked for by
/// name (`--variant exercise_...`, or the grader).
pub const EXERCISE_PREFIX: &str = "exercise_";

/// Whether `v` is an exercise (its name starts with [`EXERCISE_PREFIX`]).
pub fn is_exercise<V: ValueEnum>(v: V) -> bool {
    variant_name(v).starts_with(EXERCISE_PREFIX)
}

/// Every variant of `L` a default run shows, in report order: the
/// lesson's own, without its exercises.
pub fn all_variants<L: Lesson>() -> Vec<L::Variant> {
    let all = L::Variant::value_variants().iter().copied();
    all.filter(|&v| !is_exercise(v)).collect()
}

/// The exercises of `L`'s chapter, in order.
pub fn exercise_variants<L: Lesson>() -> Vec<L::Variant> {
    let all = L::Variant::value_variants().iter().copied();
    all.filter(|&v| is_exercise(v)).collect()
}

/// The variants `--variant` asked for (all when none), by name.
pub fn select_variants<L: Lesson>(asked: &[String]) -> Result<Vec<L::Variant>> {
    if asked.is_empty() {
        return Ok(all_variants::<L>());
    }
    asked
        .iter()
        .map(|a| {
            L::Variant::from_str(a, false).map_err(|_| {
                let known: Vec<String> = L::Variant::value_variants()
                    .iter()
                    .map(|&v| variant_name(v))
                    .collect();
                anyhow::anyhow!(
                    "--variant: unknown variant {a:?} (known: {})",
                    known.join(", ")
                )
            })
        })
        .collect()
}

/// Sets knob `name` of `variant` to `value`, after checking that the
/// variant has that knob and that the value is in its range. The window's
/// widgets and `--knob` both call this.
pub fn apply_knob<L: Lesson>(
    lesson: &mut L,
    gpu: &Gpu,
    scene: &SceneGpu,
    variant: L::Variant,
    name: &str,
    value: f64,
) -> Result<()> {
    let knobs = lesson.knobs(variant);
    let Some(knob) = knobs.iter().find(|k| k.name == name) else {
        let names: Vec<&str> = knobs.iter().map(|k| k.name).collect();
        bail!(
            "--knob {name}: {} has no such knob ({})",
            variant_name(variant),
            if names.is_empty() {
                "it has none".to_string()
            } else {
                format!("its knobs: {}", names.join(", "))
            }
        );
    };
    if let Some(why) = knob.reject(value) {
        bail!("--knob {name}={value}: {why}");
    }
    lesson.set_knob(gpu, scene, variant, name, value)
}

/// The current values of `variant`'s knobs, by name (the report's `knobs`).
pub fn knob_values<L: Lesson>(lesson: &L, variant: L::Variant) -> BTreeMap<String, f64> {
    let knobs = lesson.knobs(variant).into_iter();
    knobs.map(|k| (k.name.to_string(), k.value)).collect()
}

/// Applies every `--knob` to each of `variants` that has it; a knob that
/// none of them has is an error naming the flag.
pub fn apply_cli_knobs<L: Lesson>(
    lesson: &mut L,
    gpu: &Gpu,
    scene: &SceneGpu,
    variants: &[L::Variant],
    knobs: &[(String, f64)],
) -> Result<()> {
    for (name, value) in knobs {
        let mut used = false;
        for &v in variants {
            if lesson.knobs(v).iter().any(|k| k.name == name) {
                apply_knob(lesson, gpu, scene, v, name, *value)?;
                used = true;
            }
        }
        if !used {
            let mut all: Vec<&str> = variants
                .iter()
                .flat_map(|&v| lesson.knobs(v))
                .map(|k| k.name)
                .collect();
            all.sort();
            all.dedup();
            bail!(
                "--knob {name}: none of the variants run has it (their knobs: {})",
                if all.is_empty() {
                    "none".to_string()
                } else {
                    all.join(", ")
                }
            );
        }
    }
    Ok(())
}
