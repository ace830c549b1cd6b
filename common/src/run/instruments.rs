//! The [`Instruments`] trait: what a lesson measures and shows besides its
//! image (counters, knobs, its own buffer, extra images, pixel classes,
//! the variants an adapter cannot run). A lesson implements it in its
//! `harness.rs`, apart from its technique ([`Lesson`]); the runners call
//! both.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{bail, Result};

use crate::gpu::render::SceneGpu;
use crate::gpu::Gpu;
use crate::measure::counters::Counts;
use crate::run::knobs::Knob;
use crate::run::lesson::{variant_name, Lesson};

/// What a lesson measures and shows besides its image. Every item has a
/// default: a lesson overrides those its chapter needs.
pub trait Instruments: Lesson {
    /// Why this adapter cannot render `variant` (a missing feature, a
    /// backend that loses its precision), or `None`. A default run (no
    /// `--variant`) skips such variants with one note line each; asking for
    /// one by name is an error that prints the reason.
    fn unavailable(&self, _variant: Self::Variant) -> Option<String> {
        None
    }

    /// Counters for the report (casters drawn, fragments, ...), after
    /// [`Lesson::render`], on the frame
    /// [`Capabilities::counted_on_frame`](crate::run::lesson::Capabilities) says.
    fn counters(&self, _variant: Self::Variant) -> Counts {
        Counts::new()
    }

    /// Forgets what `variant` counted once (lessons 01–09), so that its
    /// next frames count again: the runner's `--fragile` frames, drawn with
    /// the camera moved.
    fn count_again(&mut self, _variant: Self::Variant) {}

    /// The knobs `variant` exposes ([`crate::run::knobs`]), with the values
    /// it runs with now: the parameters its chapter discusses. None by
    /// default.
    fn knobs(&self, _variant: Self::Variant) -> Vec<Knob> {
        Vec::new()
    }

    /// Sets a knob of `variant` that [`Instruments::knobs`] lists, to a
    /// value in its range (call [`apply_knob`], which checks both). The
    /// next [`Lesson::render`] of `variant` uses it.
    fn set_knob(
        &mut self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Self::Variant,
        name: &str,
        _value: f64,
    ) -> Result<()> {
        bail!("--knob {name}: {} has no knobs", variant_name(variant))
    }

    /// The lesson's own buffer for the window's "buffer" view (lessons
    /// 01–03 and 10: the shadow map; 04: the cube map's cross; 05–08: the stencil
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
}

/// A lesson's own buffer as an image, for the window's "buffer" view.
pub struct BufferView {
    /// What the image shows, in one line ("shadow map, light 0: depth, near
    /// dark").
    pub title: String,
    pub image: image::RgbaImage,
}

/// Sets knob `name` of `variant` to `value`, after checking that the
/// variant has that knob and that the value is in its range. The window's
/// widgets and `--knob` both call this.
pub fn apply_knob<L: Instruments>(
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
pub fn knob_values<L: Instruments>(lesson: &L, variant: L::Variant) -> BTreeMap<String, f64> {
    let knobs = lesson.knobs(variant).into_iter();
    knobs.map(|k| (k.name.to_string(), k.value)).collect()
}

/// Applies every `--knob` to each of `variants` that has it; a knob that
/// none of them has is an error naming the flag.
pub fn apply_cli_knobs<L: Instruments>(
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
