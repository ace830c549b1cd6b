//! Why a variant costs more than [`crate::taps::OVER`] times what its work
//! alone should: one sentence a (lesson, variants, pass, adapter), written
//! from what the variant's shader and passes do (`shaders/lesson_NN/`,
//! `lessons/lesson_NN/`), listed under each lesson's floor tables
//! (`generated/lesson_NN/tap_floor.md`, on its record page).
//!
//! A reason not yet found says so and what was measured: it starts with
//! [`NOT_YET`]. The generator fails, naming them, when a listed variant
//! has no reason here, or a reason here explains no listed variant (the
//! records changed and it no longer holds) ([`crate::over_floor::check`]).

/// Which pass is over: the lit pass against its floor, or the map passes
/// against the set's model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Pass {
    Lighting,
    Map,
}

/// Which sets a reason is for: the book's own (lavapipe, the lessons' GPU
/// work on the CPU), or a GPU's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum On {
    Lavapipe,
    Gpu,
}

/// The start of a reason not yet found.
pub const NOT_YET: &str = "Not explained yet: ";

/// One reason.
pub struct Why {
    pub lesson: &'static str,
    pub variants: &'static [&'static str],
    pub pass: Pass,
    pub on: On,
    pub why: &'static str,
}

use On::{Gpu, Lavapipe};
use Pass::{Lighting, Map};

/// The reasons, lesson by lesson. A sentence names what the variant's
/// shader or passes do beyond what its floor or the model counts; "the
/// grids' setup" is what the line through lesson 03's grids meets at no
/// comparison (each table's lead gives it: the projection into the map,
/// the receiver plane's gradient from the derivatives, the loop whose size
/// is read from a buffer), which every lookup pays and no floor counts.
pub const WHY: &[Why] = &[
    // Lesson 01: one nearest comparison (shaders/lesson_01/depth_map.wgsl).
    Why {
        lesson: "lesson_01",
        variants: &["res_256", "res_512", "res_4096"],
        pass: Lighting,
        on: Lavapipe,
        why: "A floor of one comparison leaves out the lookup's setup, which is most of a one-comparison lookup: the point projected into the map (`shadow_coords`) and tested against the map's bounds with a second product by the light's matrix (`outside_shadow_map`).",
    },
    // Lesson 02: one comparison after a receiver-side bias (bias.wgsl).
    Why {
        lesson: "lesson_02",
        variants: &[
            "none", "constant_lwjgl", "bias_0.25tx", "bias_0.5tx", "bias_1tx", "bias_4tx",
            "bias_16tx", "bias_64tx", "slope_hw", "slope_shader", "slope_unclamped",
            "normal_offset", "front_cull", "learnopengl", "wgpu_example", "bevy_bias",
        ],
        pass: Lighting,
        on: Lavapipe,
        why: "Not explained yet: the lit pass makes one comparison after `biased_receiver`, which computes every kind of bias and adds those a variant does not use as zero, yet on lavapipe it took far more over the no-shadow pass than lesson 03's one-comparison `pcf_1x1` does; lavapipe's run of lesson 02 was slow throughout, its no-shadow frame's passes taking several times lesson 01's and lesson 03's.",
    },
    Why {
        lesson: "lesson_02",
        variants: &[
            "none", "constant_lwjgl", "bias_0.25tx", "bias_0.5tx", "bias_1tx", "bias_4tx",
            "bias_16tx", "bias_64tx", "slope_hw", "slope_shader", "slope_unclamped",
            "normal_offset", "front_cull", "learnopengl", "bevy_bias",
        ],
        pass: Map,
        on: Lavapipe,
        why: "Not explained yet: most of these draw the same depth-only pass as lesson 03's filters (the same `shadow_fragments`), which lavapipe's run of lesson 03 drew in far less time; in lavapipe's run of lesson 02 the same pass took different times from variant to variant, with spreads many times wider than lesson 03's, and the record leaves a repeat out of three variants' pools because the protocol's check of the no-shadow frame's base pass failed in it.",
    },
    // Lesson 03: the filters (shaders/lesson_03/pcf.wgsl).
    Why {
        lesson: "lesson_03",
        variants: &["pcf_1x1", "pcf_3x3", "pcf_7x7"],
        pass: Lighting,
        on: Lavapipe,
        why: "The grids' setup, which the line's intercept above measures, is paid once a pixel whatever the grid's size: most of a small grid's cost, less of a larger one's, so the ratio falls towards 1× as the comparisons grow.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["pcf_1x1"],
        pass: Lighting,
        on: Gpu,
        why: "The grids' setup, which the line's intercept above measures, is paid once a pixel whatever the grid's size, and at one comparison it is most of the cost.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["hw_2x2", "wgpu_example_hw2x2"],
        pass: Lighting,
        on: Lavapipe,
        why: "One comparison after the grids' setup, which the floor leaves out, and on lavapipe that comparison is the hardware's 2×2 done in software: four texel reads and a blend.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["poisson_16"],
        pass: Lighting,
        on: Lavapipe,
        why: "Beyond the grids' setup, the disk turns by a per-pixel angle (a cosine and a sine), and each of its 16 comparisons is a bilinear one, which lavapipe does in software as four texel reads and a blend where a grid's tap reads one.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["poisson_16"],
        pass: Lighting,
        on: Gpu,
        why: "Beyond the grids' setup, the disk turns by a per-pixel angle: a cosine and a sine a pixel, and each of the 16 offsets turned by that rotation.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["poisson_16_adaptive"],
        pass: Lighting,
        on: Lavapipe,
        why: "Lavapipe shades 8 pixels at once: where one of the 8 is in a penumbra, all 8 take the four probes and the full disk, so the frame makes more comparisons than the counted mean, each a bilinear one done in software, after the grids' setup and the probes' cosines and sines.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["poisson_16_adaptive"],
        pass: Lighting,
        on: Gpu,
        why: "A GPU shades pixels in groups (32 on NVIDIA's): a group with one pixel in a penumbra waits while that pixel takes the full disk, so the time follows more comparisons than the counted mean, after the grids' setup and the four probes' cosines and sines.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["depth_avg_3x3"],
        pass: Lighting,
        on: Lavapipe,
        why: "Its one comparison comes after nine plain reads of the stored depths (`textureLoad`) and their average, which the floor of one comparison does not count, and after the grids' setup.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["depth_avg_3x3"],
        pass: Lighting,
        on: Gpu,
        why: "Its one comparison comes after nine plain reads of the stored depths (`textureLoad`) and their average, which the floor of one comparison does not count, and after the grids' setup.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["learnopengl_pcf"],
        pass: Lighting,
        on: Lavapipe,
        why: "`pcf_3x3`'s grid and setup, and LearnOpenGL's receiver bias computed at every pixel (`peer_receiver`: the texel's extent from the light's matrix, the normal turned towards the light).",
    },
    Why {
        lesson: "lesson_03",
        variants: &["learnopengl_pcf"],
        pass: Lighting,
        on: Gpu,
        why: "`pcf_3x3`'s grid and setup, and LearnOpenGL's receiver bias computed at every pixel (`peer_receiver`: the texel's extent from the light's matrix, the normal turned towards the light).",
    },
    Why {
        lesson: "lesson_03",
        variants: &["bevy"],
        pass: Lighting,
        on: Lavapipe,
        why: "Castaño's nine bilinear comparisons (each four texel reads in software) with their weights and positions computed at every pixel (six divisions), Bevy's receiver offsets (`peer_receiver`), and the grids' setup.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["castano_5x5"],
        pass: Lighting,
        on: Lavapipe,
        why: "Castaño's nine bilinear comparisons, each four texel reads and a blend in software where a grid's tap reads one texel, with their weights and positions computed at every pixel (six divisions), after the grids' setup.",
    },
    Why {
        lesson: "lesson_03",
        variants: &["bevy"],
        pass: Lighting,
        on: Gpu,
        why: "Castaño's weights and positions computed at every pixel (six divisions) before its nine comparisons, Bevy's receiver offsets (`peer_receiver`), and the grids' setup.",
    },
    // Lesson 04: the cube (shaders/lesson_04/cube_map.wgsl, peers.wgsl).
    Why {
        lesson: "lesson_04",
        variants: &[
            "linear_256", "linear_1024", "depth_1024", "depth_euclid_1024", "const_bias_1024",
            "nocull_1024", "clipped_1024", "no_range_clamp_1024",
        ],
        pass: Lighting,
        on: Gpu,
        why: "A floor of one comparison leaves out the cube lookup's setup: the flat normal from the derivatives (a cross product), the distance and tan θ of the bias, the depth the major axis gives (`receiver_depth`), and the face the direction picks.",
    },
    Why {
        lesson: "lesson_04",
        variants: &["linear_2048"],
        pass: Lighting,
        on: Gpu,
        why: "Not explained yet: its lit pass is slower than `linear_1024`'s, which differs only in the faces' size (2048² against 1024²); the rest is the cube lookup's setup, as `linear_1024`'s.",
    },
    Why {
        lesson: "lesson_04",
        variants: &["pcf3d_1024", "pcf3d_slope1_1024"],
        pass: Lighting,
        on: Gpu,
        why: "The cube lookup's setup, and for each of its 20 taps a direction of its own (an offset scaled by the texel at that distance) and a linearly filtered comparison on whichever face it falls.",
    },
    Why {
        lesson: "lesson_04",
        variants: &[
            "linear_1024", "linear_2048", "depth_1024", "depth_euclid_1024", "const_bias_1024",
            "nocull_1024", "clipped_1024", "no_range_clamp_1024", "learnopengl_1tap",
        ],
        pass: Lighting,
        on: Lavapipe,
        why: "A floor of one comparison on a 2D map leaves out the cube lookup: the flat normal from the derivatives (a cross product), the distance and tan θ of the bias, the depth the major axis gives (`receiver_depth`), and the face the direction picks with its coordinates, which lavapipe works out per pixel in software.",
    },
    Why {
        lesson: "lesson_04",
        variants: &["learnopengl_pcf20"],
        pass: Lighting,
        on: Lavapipe,
        why: "LearnOpenGL's 20 taps are nearest cube comparisons, each picking its own face and coordinates in software, after its disk's radius from the view distance and the one-tap variants' setup.",
    },
    Why {
        lesson: "lesson_04",
        variants: &["bevy_point"],
        pass: Lighting,
        on: Lavapipe,
        why: "One cube comparison after Bevy's own setup: its normal bias along the interpolated normal, scaled by the major axis' distance, and its depth bias, then the face and its coordinates picked in software.",
    },
    Why {
        lesson: "lesson_04",
        variants: &["pcf3d_1024", "pcf3d_slope1_1024"],
        pass: Lighting,
        on: Lavapipe,
        why: "Not explained yet: each of its 20 taps is a linearly filtered cube comparison (four texels, the face chosen per tap), done in software on lavapipe, and it took far longer than the 20 nearest taps of the LearnOpenGL port (`learnopengl_pcf20`).",
    },
    Why {
        lesson: "lesson_04",
        variants: &[
            "linear_256", "linear_1024", "const_bias_1024", "pcf3d_1024",
            "pcf3d_slope1_1024", "nocull_1024", "clipped_1024", "no_range_clamp_1024",
            "learnopengl_1tap", "learnopengl_pcf20",
        ],
        pass: Map,
        on: Lavapipe,
        why: "Its faces store the distance to the light, written by a fragment shader as each fragment's depth (`fs_cube_linear`): a fragment stage that the depth-only passes the model is fitted on do not have, and no early depth test.",
    },
    // Lesson 09: the cascades (shaders/lesson_09/csm.wgsl).
    Why {
        lesson: "lesson_09",
        variants: &["k2", "k3", "k4", "k4_aabb_nosnap", "k4_blend"],
        pass: Lighting,
        on: Lavapipe,
        why: "A floor of one comparison (two where the blend takes its second) leaves out the lookup's setup: the cascade chosen by a loop over the splits, the normal offset by that cascade's texel, its matrix read by index from a buffer, and the bounds test.",
    },
    Why {
        lesson: "lesson_09",
        variants: &["k4_nocull"],
        pass: Map,
        on: Lavapipe,
        why: "Not explained yet: it draws every caster into all four cascades over the whole map, the 600 m ground covering each; the model is fitted on the other variants' passes, which draw only the casters each cascade keeps, inside their scissors.",
    },
    // Lesson 10: soft shadows (shaders/lesson_10/soft.wgsl, moments.wgsl).
    Why {
        lesson: "lesson_10",
        variants: &[
            "hard_pcf", "pcf_wide_16", "pcf_wide_32", "pcss", "pcss_adaptive", "pcss_min_max", "vsm",
            "vsm_bleed_cut", "evsm", "filament_pcf", "filament_pcss", "filament_evsm",
            "bevy_gaussian", "bevy_pcss_or_pcf", "godot_pcf", "godot_soft_low", "threejs_pcf",
            "threejs_pcf_soft", "threejs_vsm",
        ],
        pass: Lighting,
        on: Lavapipe,
        why: "Each comparison is a bilinear one, four texel reads and a blend in software where a grid's tap reads one texel, on a disk turned by a per-pixel angle (a cosine and a sine) with its points read from a buffer (`soft.disk`), after the light's setup (the receiver plane's gradient, the distance from the light); PCSS's blocker search adds plain reads (`textureLoad`) and, for each blocker found, its distance inside a branch; the variance maps blend four moments by hand; `pcss_min_max`, whose floor counts PCSS's 32 at every pixel, draws the scene twice, the first draw reading eight blocks of its chain at every pixel, and its taps fall where blockers are near, the dearest pixels; the ports add their renderers' own setups.",
    },
    Why {
        lesson: "lesson_10",
        variants: &["pcf_wide_16", "pcf_wide_32"],
        pass: Lighting,
        on: Gpu,
        why: "In the code these records ran, each tap's position was computed on Vogel's spiral (a square root, a cosine and a sine a tap; since issue 50 a table turned once a pixel; `hard_pcf` turns a constant disk once), and the taps spread over a disk of 8 texels' radius.",
    },
    Why {
        lesson: "lesson_10",
        variants: &["vsm", "vsm_bleed_cut", "evsm"],
        pass: Lighting,
        on: Gpu,
        why: "Its one lookup, counted as one comparison, is four loads of 32-bit-float moments from a storage buffer, blended by hand (no filtering sampler reads them), then Chebyshev's bound (`evsm`: two warps' exponentials and two bounds).",
    },
    Why {
        lesson: "lesson_10",
        variants: &["hard_pcf"],
        pass: Lighting,
        on: Gpu,
        why: "Not explained yet: on the H200 (the code of commit `8768674`) its lit pass took far longer than on the H100 (commit `d7678c5`) for the same 16 taps of lesson 03's disk, while `pcf_wide_16` took the same on both.",
    },
];

/// The reason for one listed variant.
pub fn find(lesson: &str, variant: &str, pass: Pass, on: On) -> Option<&'static Why> {
    WHY.iter().find(|w| {
        w.lesson == lesson && w.pass == pass && w.on == on && w.variants.contains(&variant)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reason_is_plain_and_an_open_one_says_so_first() {
        for w in WHY {
            let at = format!("{} {:?}", w.lesson, w.variants);
            assert!(
                w.why.ends_with('.'),
                "{at}: a sentence ends with a full stop"
            );
            assert!(!w.variants.is_empty(), "{at}: no variant");
            // No figure typed by hand: the measured ones are in the tables.
            for unit in ["%", " ms", "µs"] {
                assert!(
                    !w.why.contains(unit),
                    "{at}: a measured-looking figure ({unit})"
                );
            }
            let open = w.why.to_lowercase().contains("not explained");
            assert_eq!(
                open,
                w.why.starts_with(NOT_YET),
                "{at}: an open reason starts with {NOT_YET:?}"
            );
        }
        // One reason a (lesson, variant, pass, adapter): no two disagree.
        for (i, a) in WHY.iter().enumerate() {
            for b in &WHY[i + 1..] {
                let same = a.lesson == b.lesson && a.pass == b.pass && a.on == b.on;
                let shared = a.variants.iter().any(|v| b.variants.contains(v));
                assert!(
                    !(same && shared),
                    "{} {:?}: two reasons",
                    a.lesson,
                    a.variants
                );
            }
        }
    }
}
