//! The tolerance table: how a number of a snapshot's line is compared,
//! by the key before it ([`Class`], [`KEYS`], [`class_of`]), and the
//! variants measured to move more than their class allows ([`OVERRIDES`],
//! [`override_of`]). What each class allows, the constants the book shows
//! (`FIGURE`, `FRAGMENTS`, `DEPTH_TESTED`), and the choice among them
//! (`tolerance_of`) are the comparison's, `tests/support/tolerance.rs`.

use common::measure::counters::{
    DEPTH_GAP_PPB_AT_HALF_FAR, DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR, FILTER_TAPS,
    FRAGMENT_SHADER_INVOCATIONS, FULL_DISK_PIXELS, PROBED_PIXELS, SHADOW_FRAGMENTS,
    SHADOW_TEXELS_WRITTEN, STENCIL_FRAGMENTS, STENCIL_UPDATES, VOLUME_FRAGMENTS,
};

/// A tolerance `abs + rel · max(|a|, |b|)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    pub abs: f64,
    pub rel: f64,
}

impl Tolerance {
    pub const EXACT: Tolerance = Tolerance { abs: 0.0, rel: 0.0 };

    /// The largest difference allowed between `a` and `b`, printed to
    /// `unit` (one unit of the last printed digit; 1 for integers).
    pub fn allowed(&self, a: f64, b: f64, unit: f64) -> f64 {
        let rounding = if *self == Tolerance::EXACT { 0.0 } else { unit };
        self.abs + self.rel * a.abs().max(b.abs()) + rounding
    }
}

/// How a number is compared, by its key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Exact,
    Figure,
    Fragments,
    DepthTested,
    /// What the adapter decides and the technique does not: pipeline
    /// statistics of fragment shader invocations (helper invocations and
    /// early depth tests are the driver's: 742 143 on the H100 against
    /// 2 627 984 on lavapipe for the same pass) and lesson 07's measured
    /// depth precision of the adapter's own pipeline. Not compared.
    AdapterDefined,
}

/// The keys compared with a tolerance; every other number is exact.
pub const KEYS: &[(&str, Class)] = &[
    ("misclassified", Class::Figure),
    ("false shadow", Class::Figure),
    ("false lit", Class::Figure),
    ("mean |dV|", Class::Figure),
    ("penumbra |dV|", Class::Figure),
    ("bleeding", Class::Figure),
    ("shimmer", Class::Figure),
    (VOLUME_FRAGMENTS.name, Class::Fragments),
    (STENCIL_FRAGMENTS.name, Class::Fragments),
    (SHADOW_FRAGMENTS.name, Class::Fragments),
    // Pixels of a class (lesson 09's cascades): receivers a rasteriser covers.
    ("pixels", Class::Fragments),
    (STENCIL_UPDATES.name, Class::DepthTested),
    (SHADOW_TEXELS_WRITTEN.name, Class::DepthTested),
    // Lesson 03's adaptive filter: the pixels it probed (the lit pass's
    // coverage inside the map), and those whose 4 probes disagreed and the
    // taps that made. Where a probe lands by a map's edge, the map's
    // rasteriser decides: 14 883 full-disk pixels on lavapipe against
    // 14 817 on an H200 (0.44 %), 989 824 taps against 988 768.
    (PROBED_PIXELS.name, Class::Fragments),
    (FULL_DISK_PIXELS.name, Class::DepthTested),
    (FILTER_TAPS.name, Class::DepthTested),
    (FRAGMENT_SHADER_INVOCATIONS.name, Class::AdapterDefined),
    (DEPTH_GAP_PPB_AT_HALF_FAR.name, Class::AdapterDefined),
    (DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR.name, Class::AdapterDefined),
];

/// Variants measured to differ more than their class allows, with why.
pub struct Override {
    /// The first word of the line: the variant.
    pub variants: &'static [&'static str],
    /// The keys it applies to.
    pub keys: &'static [&'static str],
    pub tolerance: Tolerance,
    pub measured: &'static str,
}

/// The exceptions, each with its measurement. A variant is the first word
/// of a line: the snapshots write its name, the drift test of the book's
/// tables (`tests/generated.rs`) `run/name` (`deep_range/clamp`).
pub const OVERRIDES: &[Override] = &[
    Override {
        variants: &["godot_soft_low"],
        keys: &["misclassified", "false shadow"],
        tolerance: Tolerance {
            abs: 10.0,
            rel: 0.0,
        },
        measured: "lesson 10's port of Godot's Soft Low as it ran until 60a5198, without \
                   Godot's own depth and normal bias (ported since): its untilted disk acnes \
                   the floor, and which tap self-shadows is decided by the last bit of \
                   a depth, over whole regions at once. At 640x360 on an NVIDIA H200 \
                   (2026-11-27) against lavapipe: misclassified 1.872 against 0.988 % \
                   on the contact scene, 8.338 against 2.274 % on the large light, \
                   false shadow 1.844 against 0.749 and 8.335 against 2.246 %, beyond \
                   both runs' bounds (0.458, 2.369). Its figures are checked exactly \
                   on lavapipe",
    },
    Override {
        variants: &["learnopengl_pcf20"],
        keys: &["misclassified"],
        tolerance: Tolerance {
            abs: 0.08,
            rel: 0.0,
        },
        measured: "lesson 04's LearnOpenGL 20-tap kernel: misclassified 0.28 % \
                   (lavapipe, llvmpipe) against 0.34 % (H100) at 320x180, 0.299 against \
                   0.342 at 640x360",
    },
    Override {
        variants: &["learnopengl_pcf20"],
        keys: &["false shadow", "false lit"],
        tolerance: Tolerance {
            abs: 0.35,
            rel: 0.0,
        },
        measured: "the same kernel trades false lit for false shadow: 320x180, false \
                   shadow 0.02 % and false lit 0.26 % (lavapipe, llvmpipe) against 0.30 % \
                   and 0.04 % (H100); 640x360: 0.028 and 0.271 against 0.311 and 0.031",
    },
    Override {
        variants: &["spot_wide/none", "spot_wide/bias_0.25tx"],
        keys: &["misclassified", "false shadow", "mean |dV|"],
        tolerance: Tolerance { abs: 1.5, rel: 0.0 },
        measured: "lesson 02's unbiased and nearly unbiased maps under the wide spot \
                   light (lesson_02_spot_wide.toml, 640x360), whose false shadow is acne: \
                   which texel self-shadows is decided by the last bit of a depth. none \
                   48.17 % (lavapipe) against 47.39 % (llvmpipe), bias_0.25tx 3.23 \
                   against 2.54 %",
    },
    Override {
        variants: &[
            "deep_range/neither",
            "deep_range/clamp",
            "deep_range/infinite",
        ],
        keys: &["misclassified", "false shadow", "false lit", "mean |dV|"],
        tolerance: Tolerance { abs: 2.0, rel: 0.0 },
        measured: "lesson 07's standard depth on the deep range (lesson_07_deep_range.toml, \
                   640x360), the negative control: the casters z-fight with the floor, and \
                   which pixel wins is the rasteriser's. neither and clamp misclassify \
                   1.889 % (lavapipe) against 1.073 % (llvmpipe), false shadow 1.233 \
                   against 0.168 %; infinite 1.422 against 1.170 %",
    },
];

/// The class of the number after `words` (the text since the previous
/// number on its line): the longest key that `words` ends with.
pub fn class_of(words: &str) -> (Class, &'static str) {
    let words = words.trim();
    KEYS.iter()
        .filter(|(k, _)| words.ends_with(k))
        .max_by_key(|(k, _)| k.len())
        .map(|&(k, c)| (c, k))
        .unwrap_or((Class::Exact, ""))
}

/// The [`OVERRIDES`] entry for `key` on a line of `variant`, if any.
pub fn override_of(key: &str, variant: &str) -> Option<Tolerance> {
    // `run/variant` names one scene's variant; a bare name, every scene's.
    let named =
        |v: &&str| variant == *v || (!v.contains('/') && variant.ends_with(&format!("/{v}")));
    OVERRIDES
        .iter()
        .find(|o| o.variants.iter().any(named) && o.keys.contains(&key))
        .map(|o| o.tolerance)
}
