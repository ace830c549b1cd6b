//! Lesson 02's knobs ([`common::run::knobs`]): the sizes of the biases the
//! chapter discusses, on top of the named variants.
//!
//! A variant exposes the parameters its own fix sets, and only those:
//!
//! - a receiver bias ([`ShadowBias`]) shows a knob for each field its
//!   default sets (non-zero): `bias_*tx` the constant in texels,
//!   `slope_shader` the constant, the slope factor and its clamp,
//!   `normal_offset` the constant and the normal offset, `constant_lwjgl`
//!   its depth, and the renderers' defaults their own parameters. A knob
//!   the variant's fix does not use would turn it into another variant
//!   (`none` has none: it is lesson 01's comparison). `slope_unclamped` has
//!   no clamp knob: having none is what it is (`slope_shader` with
//!   `slope_clamp` at 64 texels clamps only beyond tan θ = 64 / `slope`,
//!   past 89° at `slope` 1, where cos θ < 0.05 and the report counts no
//!   receiver);
//! - a hardware bias ([`SlopeScaledBias`]: `slope_hw`, `wgpu_example`)
//!   shows the rasteriser's three numbers, the clamp in texels (0: no
//!   clamp, as `DepthBiasState` has it).
//!
//! The hardware knobs have their own names (`hw_...`), so that one
//! `--knob` never sets two different things in two variants of a run.

use anyhow::{bail, Result};
use common::run::knobs::{Knob, KnobRange};

use super::bias::{ShadowBias, SlopeScaledBias};

/// One knob of [`ShadowBias`]: its field, name, doc and range.
struct ReceiverKnob {
    name: &'static str,
    doc: &'static str,
    range: KnobRange,
    field: fn(&mut ShadowBias) -> &mut f32,
}

pub const fn float(min: f64, max: f64, log: bool) -> KnobRange {
    KnobRange::Float { min, max, log }
}

/// The receiver's knobs, in the order the window lists them.
const RECEIVER: [ReceiverKnob; 8] = [
    ReceiverKnob {
        name: "bias_texels",
        doc: "constant bias: the receiver moves this many texels (along its depth gradient) towards the light",
        range: float(0.0, 64.0, true),
        field: |b| &mut b.toward_light,
    },
    ReceiverKnob {
        name: "slope",
        doc: "slope scaling: plus slope × tan θ texels towards the light (a receiver at θ needs tan θ / 2)",
        range: float(0.0, 8.0, false),
        field: |b| &mut b.slope,
    },
    ReceiverKnob {
        name: "slope_clamp",
        doc: "the slope term's clamp, in texels: where slope × tan θ exceeds it, a steep receiver gets less than it needs",
        range: float(0.0, 64.0, true),
        field: |b| &mut b.slope_max,
    },
    ReceiverKnob {
        name: "normal_texels",
        doc: "normal offset: the receiver moves normal_texels × (1 − cos θ) texels along its normal",
        range: float(0.0, 16.0, false),
        field: |b| &mut b.normal,
    },
    ReceiverKnob {
        name: "bias_depth",
        doc: "subtracted from the receiver's depth, in depth units (the lwjgl book's 0.05; LearnOpenGL's least, 0.005)",
        range: float(0.0, 0.2, true),
        field: |b| &mut b.depth,
    },
    ReceiverKnob {
        name: "bias_depth_slope",
        doc: "LearnOpenGL's max(bias_depth_slope × (1 − cos θ), bias_depth) depth units",
        range: float(0.0, 0.2, false),
        field: |b| &mut b.depth_slope,
    },
    ReceiverKnob {
        name: "bias_world_m",
        doc: "Bevy's depth bias: the receiver moves this many metres towards the light, whatever the texel",
        range: float(0.0, 0.5, true),
        field: |b| &mut b.toward_light_world,
    },
    ReceiverKnob {
        name: "normal_flat_texels",
        doc: "Bevy's normal bias: the receiver moves this many texels (the texel's larger side) along its normal",
        range: float(0.0, 16.0, false),
        field: |b| &mut b.normal_flat,
    },
];

/// An `f32` as the `f64` it prints as (0.1, not 0.10000000149011612): the
/// value a knob was set to, or the variant's default.
fn widen(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(x as f64)
}

/// The knobs of a variant whose receiver bias is `default` when named, with
/// the values of `now`: one per field `default` sets (a finite one).
pub fn receiver_knobs(default: ShadowBias, now: ShadowBias) -> Vec<Knob> {
    let (mut default, mut now) = (default, now);
    RECEIVER
        .iter()
        .filter(|k| {
            let d = *(k.field)(&mut default);
            d != 0.0 && d.is_finite() && d < f32::MAX
        })
        .map(|k| Knob {
            name: k.name,
            doc: k.doc,
            range: k.range,
            value: widen(*(k.field)(&mut now)),
        })
        .collect()
}

/// Sets receiver knob `name` of `bias` to `value` (checked by `apply_knob`).
pub fn set_receiver(bias: &mut ShadowBias, name: &str, value: f64) -> Result<()> {
    let Some(k) = RECEIVER.iter().find(|k| k.name == name) else {
        bail!("--knob {name}: not a receiver bias knob");
    };
    *(k.field)(bias) = value as f32;
    Ok(())
}

/// The knobs of a hardware (rasteriser) bias, with its values now.
pub fn hardware_knobs(b: SlopeScaledBias) -> Vec<Knob> {
    vec![
        Knob {
            name: "hw_slope_scale",
            doc: "the rasteriser adds hw_slope_scale × the triangle's depth slope per texel to each stored depth",
            range: float(0.0, 8.0, false),
            value: widen(b.slope_scale),
        },
        Knob {
            name: "hw_constant",
            doc: "plus hw_constant units of the depth format (for Depth32Float, 2^(e − 23): rounding)",
            range: KnobRange::Int { min: 0, max: 256 },
            value: b.constant as f64,
        },
        Knob {
            name: "hw_clamp_texels",
            doc: "at most this many texels of depth at the scene's centre (0: no clamp; GL cannot clamp)",
            range: float(0.0, 64.0, true),
            value: widen(b.clamp_texels),
        },
    ]
}

/// Sets hardware knob `name` of `b` to `value` (checked by `apply_knob`).
pub fn set_hardware(b: &mut SlopeScaledBias, name: &str, value: f64) -> Result<()> {
    match name {
        "hw_slope_scale" => b.slope_scale = value as f32,
        "hw_constant" => b.constant = value as i32,
        "hw_clamp_texels" => b.clamp_texels = value as f32,
        _ => bail!("--knob {name}: not a hardware bias knob"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_variant_gets_the_knobs_its_bias_sets() {
        let slope = ShadowBias {
            toward_light: 0.1,
            slope: 1.0,
            slope_max: 4.0,
            ..ShadowBias::NONE
        };
        let names = |b| {
            receiver_knobs(b, b)
                .iter()
                .map(|k| k.name)
                .collect::<Vec<_>>()
        };
        assert_eq!(names(slope), ["bias_texels", "slope", "slope_clamp"]);
        let unclamped = ShadowBias {
            slope_max: f32::MAX,
            ..slope
        };
        assert_eq!(names(unclamped), ["bias_texels", "slope"]);
        assert!(names(ShadowBias::NONE).is_empty());
        let k = receiver_knobs(slope, slope);
        assert_eq!(k[0].value, 0.1, "the default as written, not as an f32");
        let mut b = slope;
        set_receiver(&mut b, "slope_clamp", 16.0).unwrap();
        assert_eq!(b.slope_max, 16.0);
        assert!(set_receiver(&mut b, "hw_constant", 1.0).is_err());
    }
}
