//! What the GPUs of the book's other sets are, so that a reader can scale
//! their times to a card of their own: each set's note, written beside
//! its tables ([`crate::sets`], [`crate::taps`], the choosing chapter's
//! GPU table in [`crate::gpu_costs`]).
//!
//! The hardware's figures are NVIDIA's, from the pages [`HOPPER`] and
//! [`TURING`] (each constant quotes its line). The rate beside
//! them is the workbook's own: the shadow-map comparisons a second the set
//! made on lesson 03's grids ([`crate::taps::Rate`]).
//!
//! An H100 is a data-centre GPU: of its 66 TPCs only 2 run vertex,
//! geometry and pixel shaders, so the lit passes and the shadow passes of
//! every lesson run on a small fraction of the chip, and a desktop GPU
//! takes far more texture samples a second. NVIDIA's article gives no such
//! figure for the H200; the note says so, and sets the H200's measured
//! rate beside the H100's.

use crate::origins::{gpu, origin, Gpu};
use crate::record::Record;
use crate::taps::Rate;

/// A published source.
pub struct Source {
    pub title: &'static str,
    pub url: &'static str,
    pub year: u32,
}

impl Source {
    /// `[title](url), year`.
    pub fn cite(&self) -> String {
        format!("[{}]({}), {}", self.title, self.url, self.year)
    }
}

/// NVIDIA Technical Blog, Michael Andersch, 22 March 2022: "The NVIDIA
/// H100 GPU with SXM5 board form-factor includes the following units:
/// 8 GPCs, 66 TPCs, 2 SMs/TPC, 132 SMs per GPU" and "Only two TPCs in both
/// the SXM5 and PCIe H100 GPUs are graphics-capable (that is, they can run
/// vertex, geometry, and pixel shaders)."
pub const HOPPER: Source = Source {
    title: "NVIDIA Hopper Architecture In-Depth",
    url: "https://developer.nvidia.com/blog/nvidia-hopper-architecture-in-depth/",
    year: 2022,
};

/// The H100 SXM5's TPCs ([`HOPPER`]).
pub const H100_TPCS: u32 = 66;
/// Those of them that can run vertex, geometry and pixel shaders ([`HOPPER`]).
pub const H100_GRAPHICS_TPCS: u32 = 2;

/// NVIDIA Technical Blog, Emmett Kilgariff, 14 September 2018,
/// Table 1 ("Comparison of NVIDIA Pascal GP102 and Turing TU102"), the
/// GeForce RTX 2080 Ti's column: TPCs 34, ROPs 88, Texture Units 272,
/// "Texel Fill-rate (Gigatexels/sec)" 420.2 (reference) / 444.7 (Founders
/// Edition).
pub const TURING: Source = Source {
    title: "NVIDIA Turing Architecture In-Depth",
    url: "https://developer.nvidia.com/blog/nvidia-turing-architecture-in-depth/",
    year: 2018,
};

/// A desktop GPU's published figures.
pub struct Desktop {
    pub name: &'static str,
    /// Peak texel fill rate, reference board, G texels a second.
    pub texel_rate_g: f64,
    pub texture_units: u32,
    pub tpcs: u32,
    pub source: &'static Source,
}

/// The desktop GPU the notes compare with ([`TURING`], Table 1).
pub const RTX_2080_TI: Desktop = Desktop {
    name: "GeForce RTX 2080 Ti",
    texel_rate_g: 420.2,
    texture_units: 272,
    tpcs: 34,
    source: &TURING,
};

/// What the GPU is, in NVIDIA's figures.
fn what(gpu: Gpu) -> String {
    let tpcs = format!(
        "only {H100_GRAPHICS_TPCS} of the H100's {H100_TPCS} TPCs can run vertex, geometry and pixel shaders ({})",
        HOPPER.cite()
    );
    match gpu {
        Gpu::H100 => format!(
            "the NVIDIA H100 is a data-centre GPU: {tpcs}, so every pass of these lessons runs on a small fraction of the chip, and a desktop GPU shades and samples far faster"
        ),
        Gpu::H200 => format!(
            "the NVIDIA H200 is a data-centre GPU of the H100's Hopper architecture; {tpcs}, and the article gives no such figure for the H200"
        ),
    }
}

/// The set's note: what its GPU is and, when its lesson 03 gives a rate
/// (`rate_g`: G comparisons a second), that rate against a desktop GPU's
/// published texel rate and how to scale by it. `h100_rate_g`: the H100
/// set's own rate, set beside an H200's. `None` for a set whose GPU the
/// notes do not know (lavapipe's is said where its tables are).
pub fn note(set: &str, rate_g: Option<f64>, h100_rate_g: Option<f64>) -> Option<String> {
    let gpu = gpu(set)?;
    let mut s = what(gpu);
    if let Some(r) = rate_g {
        let d = &RTX_2080_TI;
        s += &format!(
            ". On lesson 03's grids it made {r:.1} G shadow-map comparisons a second (every pixel of the frame counted; [the tap floor](lesson_03_records.md#the-tap-floor))"
        );
        if let (Gpu::H200, Some(h)) = (gpu, h100_rate_g) {
            s += &format!(" (the H100's set: {h:.1} G)");
        }
        s += &format!(
            "; NVIDIA gives the {} {:.1} G texels a second from its {} texture units on {} TPCs ({}), {:.0} times as many. As a rough guide, a time bound by its comparisons here scales to such a card by this rate over the card's texel rate ({:.2} for the {})",
            d.name,
            d.texel_rate_g,
            d.texture_units,
            d.tpcs,
            d.source.cite(),
            d.texel_rate_g / r,
            r / d.texel_rate_g,
            d.name
        );
    }
    Some(s)
}

/// The note of the set `name` among `sets` ([`note`]), its rate and the
/// H100's measured on their own lesson 03 ([`Rate`]).
pub fn set_note(name: &str, sets: &[(String, Vec<Record>)]) -> Option<String> {
    let rate_of = |set: &str, records: &[Record]| {
        Rate::of(records, origin(set).map(|o| o.commit)).map(|r| r.per_second_g())
    };
    let (_, records) = sets.iter().find(|(n, _)| n == name)?;
    let h100 = sets
        .iter()
        .find(|(n, _)| gpu(n) == Some(Gpu::H100))
        .and_then(|(n, r)| rate_of(n, r));
    note(name, rate_of(name, records), h100)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_notes_know_the_sets_and_scale_by_the_measured_rate() {
        assert_eq!(gpu("nvidia-h100-80gb-hbm3-vulkan"), Some(Gpu::H100));
        assert_eq!(gpu("nvidia-h200-vulkan"), Some(Gpu::H200));
        assert_eq!(gpu("llvmpipe-llvm-15-0-6-256-bits-gl"), None);
        let n = note("nvidia-h100-80gb-hbm3-vulkan", Some(42.02), None).expect("a note");
        assert!(n.contains("only 2 of the H100's 66 TPCs"), "{n}");
        assert!(n.contains("42.0 G shadow-map comparisons"), "{n}");
        // 420.2 / 42.02 = 10 times as many; 42.02 / 420.2 = 0.10.
        assert!(
            n.contains("10 times as many") && n.contains("(0.10 for"),
            "{n}"
        );
        let h200 = note("nvidia-h200-vulkan", Some(38.0), Some(37.9)).expect("a note");
        assert!(
            h200.contains("no such figure for the H200")
                && h200.contains("(the H100's set: 37.9 G)")
        );
        // Without a rate, what the GPU is, and nothing measured.
        let bare = note("nvidia-h200-vulkan", None, None).expect("a note");
        assert!(!bare.contains("G shadow-map"), "{bare}");
    }
}
