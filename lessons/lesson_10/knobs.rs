//! Lesson 10's knobs ([`common::run::knobs`]): a fixed disk's radius, a
//! PCSS's taps and its receiver plane, a variance map's blur and its
//! light-bleeding cut. The renderers' defaults and the exercises have none:
//! those are someone else's settings and the student's code.

use anyhow::{bail, Result};
use common::run::knobs::{Knob, KnobRange};

use super::soft::{Search, Technique};
use crate::lesson_02::knobs::float;

/// PCSS's knob for the filter's taps.
pub const FILTER_TAPS_KNOB: &str = "filter_taps"; // not a counter: the knob

/// The most taps a search or a filter may take: the disk table's points.
pub const MAX_TAPS: u32 = super::soft::DISK_POINTS as u32;

/// The knobs of `t`, with its values now.
pub fn technique_knobs(t: Technique) -> Vec<Knob> {
    let taps = |name, doc, value: u32| Knob {
        name,
        doc,
        range: KnobRange::Int {
            min: 1,
            max: MAX_TAPS as i64,
        },
        value: value as f64,
    };
    match t {
        Technique::FixedDisk { radius_texels, .. } => vec![Knob {
            name: "kernel_radius_texels",
            doc: "the fixed disk's radius, in texels: one penumbra width for every blocker",
            range: float(0.5, 64.0, true),
            value: radius_texels as f64,
        }],
        Technique::Pcss(p) => vec![
            taps("search_taps", "blocker-search taps: fewer miss thin blockers", p.search_taps),
            taps(FILTER_TAPS_KNOB, "filter taps: fewer give a noisier penumbra", p.filter_taps),
            Knob {
                name: "min_filter_texels",
                doc: "the least filter radius, in texels: above 0 the contact shadow blurs open",
                range: float(0.0, 16.0, false),
                value: p.min_filter_texels as f64,
            },
            Knob {
                name: "search_at_receiver",
                doc: "search only the light's size at the receiver (Filament's), not every blocker up to the nearest caster",
                range: KnobRange::Toggle,
                value: (p.search == Search::LightSizeAtReceiver) as u32 as f64,
            },
            Knob {
                name: "min_max",
                doc: "ask the map's min/max chain first: lit or umbra without a tap where it can tell, the same answer",
                range: KnobRange::Toggle,
                value: p.min_max as u32 as f64,
            },
            Knob {
                name: "chain_only",
                doc: "with min_max: the chain's answers only (a diagnostic: its error figures are of this image), black where it answers umbra or cannot tell",
                range: KnobRange::Toggle,
                value: p.chain_only as u32 as f64,
            },
            Knob {
                name: "receiver_plane",
                doc: "compare each tap with the receiver's plane there (off: acne under wide kernels at grazing light)",
                range: KnobRange::Toggle,
                value: p.receiver_plane as u32 as f64,
            },
        ],
        Technique::Variance(v) => vec![
            Knob {
                name: "blur_texels",
                doc: "the moments' box blur radius, in texels: the penumbra's one width",
                range: KnobRange::Int { min: 0, max: 16 },
                value: v.blur as f64,
            },
            Knob {
                name: "bleed_cut",
                doc: "light-bleeding reduction: visibilities below it become 0, the rest stretch to [0, 1]",
                range: float(0.0, 0.9, false),
                value: v.bleed.0 as f64,
            },
        ],
        _ => Vec::new(),
    }
}

/// Sets knob `name` of `t` to `value` (checked by `apply_knob`).
pub fn set_technique_knob(t: &mut Technique, name: &str, value: f64) -> Result<()> {
    match (t, name) {
        (Technique::FixedDisk { radius_texels, .. }, "kernel_radius_texels") => {
            *radius_texels = value as f32
        }
        (Technique::Pcss(p), "search_taps") => p.search_taps = value as u32,
        (Technique::Pcss(p), FILTER_TAPS_KNOB) => p.filter_taps = value as u32,
        (Technique::Pcss(p), "receiver_plane") => p.receiver_plane = value != 0.0,
        (Technique::Pcss(p), "min_max") => p.min_max = value != 0.0,
        (Technique::Pcss(p), "chain_only") => p.chain_only = value != 0.0,
        (Technique::Pcss(p), "min_filter_texels") => p.min_filter_texels = value as f32,
        (Technique::Pcss(p), "search_at_receiver") => {
            p.search = match value != 0.0 {
                true => Search::LightSizeAtReceiver,
                false => Search::NearestCaster,
            }
        }
        (Technique::Variance(v), "blur_texels") => v.blur = value as u32,
        (Technique::Variance(v), "bleed_cut") => v.bleed.0 = value as f32,
        (t, _) => bail!("--knob {name}: the technique {t:?} has no such knob"),
    }
    Ok(())
}
