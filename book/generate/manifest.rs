//! What the book shows, and which run makes it: every lesson on its default
//! scene (timed) and on every extreme-case scene a chapter cites (error and
//! counters only), and which output file of which run each figure is.
//!
//! `tests/generated.rs` reads this list too: it re-runs every entry and
//! checks the committed tables' error columns and counters.

/// The book's resolution: every run, every table, every figure.
pub const WIDTH: u32 = 640;
pub const HEIGHT: u32 = 360;
/// The timing protocol (documented once, in the book's using.md): each timed
/// run renders 2 warm-up frames, then `FRAMES` timed ones, in a fresh
/// process, `REPEATS` times. Tables quote the median of the
/// `REPEATS × FRAMES` frame times and their spread (`record::Stat::of_runs`).
pub const REPEATS: u32 = 3;
pub const FRAMES: u32 = 5;
/// The backend the committed tables were made on (the drift test pins it).
pub const BACKEND: &str = "vulkan";
/// The adapter every record is made on: a software rasteriser (llvmpipe),
/// so the tables do not depend on the machine's GPU, and the drift tests
/// (`tests/generated.rs`) can repeat them anywhere Mesa is installed.
pub const ADAPTER: &str = "software";

/// Lessons whose tables show the mean |ΔV| (fractional visibility).
pub const MEAN_ABS_LESSONS: &[&str] = &["lesson_03", "lesson_09", "lesson_10"];

/// One run of one lesson.
#[derive(Clone, Copy, Debug)]
pub struct Run {
    pub lesson: &'static str,
    /// The file name under `book/src/generated/<lesson>/` (no extension).
    pub name: &'static str,
    /// Scene file, relative to the repository root; `None`: the default.
    pub scene: Option<&'static str>,
    /// A short description for the scenes table.
    pub title: &'static str,
    /// Timed runs are repeated and their tables carry times; the others
    /// carry error and counters only.
    pub timed: bool,
    /// Only these variants (all when empty).
    pub variants: &'static [&'static str],
    /// The frame size and timed frames per repeat: the book's
    /// ([`WIDTH`]×[`HEIGHT`], [`FRAMES`]) except for [`interactive`] runs.
    pub size: (u32, u32),
    pub frames: u32,
}

impl Run {
    pub fn id(&self) -> String {
        format!("{}/{}", self.lesson, self.name)
    }
}

/// A lesson on its default scene, timed: its `results` table.
const fn default(lesson: &'static str) -> Run {
    Run {
        lesson,
        name: "results",
        scene: None,
        title: "default scene",
        timed: true,
        variants: &[],
        size: (WIDTH, HEIGHT),
        frames: FRAMES,
    }
}

/// An extreme case: another scene, errors and counters only; the other
/// fields as [`default`]'s.
const fn case(
    lesson: &'static str,
    name: &'static str,
    scene: &'static str,
    title: &'static str,
) -> Run {
    Run {
        name,
        scene: Some(scene),
        title,
        timed: false,
        ..default(lesson)
    }
}

/// A timed run of some variants on another scene (its table has times).
const fn timed_case(
    lesson: &'static str,
    name: &'static str,
    scene: &'static str,
    title: &'static str,
    variants: &'static [&'static str],
) -> Run {
    Run {
        timed: true,
        variants,
        ..case(lesson, name, scene, title)
    }
}

/// The size a reader's window opens at, where 33 ms a frame is the bar
/// for interactive (30 frames a second).
pub const INTERACTIVE: (u32, u32) = (1280, 720);
/// Timed frames per repeat of an [`interactive`] run.
pub const INTERACTIVE_FRAMES: u32 = 10;

/// The name of the [`interactive`] runs.
pub const HD: &str = "hd";

/// A lesson's recommended variants on its default scene at
/// [`INTERACTIVE`] size (`book/src/generated/<lesson>/hd.md`).
const fn interactive(lesson: &'static str, variants: &'static [&'static str]) -> Run {
    Run {
        name: HD,
        title: "default scene at 1280×720",
        variants,
        size: INTERACTIVE,
        frames: INTERACTIVE_FRAMES,
        ..default(lesson)
    }
}

/// The three ways to build shadow volumes (lesson 05), timed on the big meshes.
const BUILD_VARIANTS: &[&str] = &["zpass_cpu", "zpass_quads", "zpass_compute"];

/// Every run, in chapter order.
#[rustfmt::skip]
pub const RUNS: &[Run] = &[
    default("lesson_01"),
    interactive("lesson_01", &["res_2048"]),
    default("lesson_02"),
    interactive("lesson_02", &["front_cull"]),
    case("lesson_02", "contact", "scenes/lesson_02_contact.toml", "a cube resting on the floor"),
    case("lesson_02", "grazing_80", "scenes/lesson_02_grazing_80.toml", "light 80° from the floor's normal"),
    case("lesson_02", "grazing_85", "scenes/lesson_02_grazing_85.toml", "light 85° from the floor's normal"),
    case("lesson_02", "grazing_89", "scenes/lesson_02_grazing_89.toml", "light 89° from the floor's normal"),
    case("lesson_02", "thin_plate", "scenes/lesson_02_thin_plate.toml", "a 2 cm plate above the floor"),
    case("lesson_02", "far", "scenes/lesson_02_far.toml", "the scene 10 km from the origin"),
    case("lesson_02", "spot_wide", "scenes/lesson_02_spot_wide.toml", "a wide spot light far away"),
    default("lesson_03"),
    interactive("lesson_03", &["poisson_16"]),
    case("lesson_03", "closeup", "scenes/lesson_03_closeup.toml", "close-up of one shadow edge"),
    case("lesson_03", "grazing_85", "scenes/lesson_02_grazing_85.toml", "light 85° from the floor's normal"),
    case("lesson_03", "thin_plate", "scenes/lesson_02_thin_plate.toml", "a 2 cm plate above the floor"),
    case("lesson_03", "far", "scenes/lesson_02_far.toml", "the scene 10 km from the origin"),
    case("lesson_03", "spot_wide", "scenes/lesson_02_spot_wide.toml", "a wide spot light far away"),
    default("lesson_04"),
    interactive("lesson_04", &["depth_1024", "linear_2048"]),
    case("lesson_04", "seams", "scenes/lesson_04_seams.toml", "shadows across cube edges and corners"),
    case("lesson_04", "near_caster", "scenes/lesson_04_near_caster.toml", "a caster 3 cm from the light"),
    case("lesson_04", "beyond_range", "scenes/lesson_04_beyond_range.toml", "a wall past the light's range"),
    case("lesson_04", "far_origin", "scenes/lesson_04_far_origin.toml", "the scene far from the origin"),
    case("lesson_04", "axes_pos", "scenes/lesson_04_axes_pos.toml", "one caster on each + axis"),
    case("lesson_04", "axes_neg", "scenes/lesson_04_axes_neg.toml", "one caster on each − axis"),
    default("lesson_05"),
    interactive("lesson_05", &["zpass_cpu", "zpass_compute"]),
    timed_case("lesson_05", "holed", "scenes/lesson_05_holed.toml", "a closed mesh of 50k+ triangles with holes punched in it (casts two-sided)", BUILD_VARIANTS),
    timed_case("lesson_05", "dense", "scenes/lesson_05_dense.toml", "a closed mesh of about 100k triangles", BUILD_VARIANTS),
    case("lesson_05", "eye_in_umbra", "scenes/volume_eye_in_umbra.toml", "the eye inside a shadow"),
    case("lesson_05", "near_slice", "scenes/volume_near_slice.toml", "the near plane slicing a volume"),
    case("lesson_05", "open_quad", "scenes/volume_open_quad.toml", "an open caster (one quad)"),
    case("lesson_05", "mirrored", "scenes/volume_mirrored.toml", "mirrored models (negative scale)"),
    default("lesson_06"),
    interactive("lesson_06", &["zfail_selective"]),
    case("lesson_06", "eye_in_umbra", "scenes/volume_eye_in_umbra.toml", "the eye inside a shadow"),
    case("lesson_06", "near_slice", "scenes/volume_near_slice.toml", "the near plane slicing a volume"),
    case("lesson_06", "open_quad", "scenes/volume_open_quad.toml", "an open caster (one quad)"),
    case("lesson_06", "nonmanifold", "scenes/volume_nonmanifold.toml", "a non-manifold edge (4 faces)"),
    case("lesson_06", "degenerate", "scenes/volume_degenerate.toml", "degenerate and edge-on triangles"),
    case("lesson_06", "mirrored", "scenes/volume_mirrored.toml", "mirrored models (negative scale)"),
    case("lesson_06", "uv_seam", "scenes/volume_uv_seam.toml", "a sphere with UV seams"),
    case("lesson_06", "nested_256", "scenes/volume_nested_256.toml", "256 nested volumes (the stencil wraps)"),
    case("lesson_06", "finite_far_open", "scenes/lesson_06_finite_far_open.toml", "far = 200: an open tube, the eye in its shadow"),
    case("lesson_06", "finite_far_cutout", "scenes/lesson_06_finite_far_cutout.toml", "far = 200: a flat star cut-out, spot light"),
    case("lesson_06", "finite_far_close_light", "scenes/lesson_06_finite_far_close_light.toml", "far = 200: a point light 0.3 above a box"),
    case("lesson_06", "finite_far_back_cap", "scenes/lesson_06_finite_far_back_cap.toml", "far = 200: the back cap inside the far plane"),
    default("lesson_07"),
    interactive("lesson_07", &["infinite"]),
    case("lesson_07", "deep_range", "scenes/lesson_07_deep_range.toml", "near 1e-3, far 1e5, the objects 400 units away"),
    case("lesson_07", "near_1e-3_far_1e5", "scenes/lesson_07_near_1e-3_far_1e5.toml", "near 1e-3, far 1e5"),
    case("lesson_07", "far_200", "scenes/lesson_08_far_200.toml", "lesson 08's scene, far = 200"),
    case("lesson_07", "far_crossing", "scenes/lesson_08_far_crossing.toml", "far = 15, through two range spheres"),
    default("lesson_08"),
    interactive("lesson_08", &["bounds_scissor", "cull_bounds_scissor"]),
    case("lesson_08", "lesson_07_scene", "scenes/lesson_07.toml", "lesson 07's scene (far = 16)"),
    case("lesson_08", "far_200", "scenes/lesson_08_far_200.toml", "far = 200"),
    case("lesson_08", "far_crossing", "scenes/lesson_08_far_crossing.toml", "far = 15, through two range spheres"),
    case("lesson_08", "near_1e-3_far_1e5", "scenes/lesson_07_near_1e-3_far_1e5.toml", "near 1e-3, far 1e5"),
    case("lesson_08", "near_crossing", "scenes/lesson_08_near_crossing.toml", "a range sphere crossing the near plane"),
    case("lesson_08", "camera_inside", "scenes/lesson_08_camera_inside.toml", "the camera inside a range sphere"),
    case("lesson_08", "nested_128", "scenes/lesson_08_nested_128.toml", "128 nested volumes"),
    default("lesson_09"),
    interactive("lesson_09", &["k4", "k4_aabb"]),
    case("lesson_09", "look_down", "scenes/lesson_09_look_down.toml", "the camera looking straight down"),
    case("lesson_09", "grazing", "scenes/lesson_09_grazing.toml", "the light almost parallel to the ground"),
    case("lesson_09", "far_10km", "scenes/lesson_09_far_10km.toml", "far plane at 10 km"),
    case("lesson_09", "offscreen_caster", "scenes/lesson_09_offscreen_caster.toml", "a caster outside the view shadows what is inside it"),
    case("lesson_09", "contact_boundary", "scenes/lesson_09_contact_boundary.toml", "a cascade boundary across a contact shadow"),
    default("lesson_10"),
    interactive("lesson_10", &["pcss", "pcss_min_max", "filament_pcss"]),
    case("lesson_10", "contact", "scenes/lesson_10_contact.toml", "cube and sphere resting on the floor, a 2° sun"),
    case("lesson_10", "large_light", "scenes/lesson_10_large_light.toml", "a spot light of 1 m radius"),
    case("lesson_10", "overlap", "scenes/lesson_10_overlap.toml", "blockers at two heights side by side"),
    case("lesson_10", "thin", "scenes/lesson_10_thin.toml", "a thin sheet's edge over a box"),
    case("lesson_10", "grazing", "scenes/lesson_10_grazing.toml", "a 1° sun 80° from the floor's normal"),
];

/// A figure the book shows: `file` of run `run` (its id), copied to
/// `book/src/figures/<dest>`.
#[derive(Clone, Copy, Debug)]
pub struct Figure {
    pub run: &'static str,
    pub file: &'static str,
    pub dest: &'static str,
}

const fn fig(run: &'static str, file: &'static str, dest: &'static str) -> Figure {
    Figure { run, file, dest }
}

/// Every image of a run that the book shows.
#[rustfmt::skip]
pub const FIGURES: &[Figure] = &[
    fig("lesson_01/results", "res_1024_depth_map.png", "lesson_01/res_1024_depth_map.png"),
    fig("lesson_01/results", "res_256.png", "lesson_01/res_256.png"),
    fig("lesson_01/results", "res_4096.png", "lesson_01/res_4096.png"),
    fig("lesson_01/results", "res_256_diff_l0.png", "lesson_01/res_256_diff_l0.png"),
    fig("lesson_01/results", "res_4096_diff_l0.png", "lesson_01/res_4096_diff_l0.png"),
    fig("lesson_01/results", "reference_visibility_l0.png", "lesson_01/reference_visibility_l0.png"),
    fig("lesson_02/results", "none_diff_l0.png", "lesson_02/none_diff.png"),
    fig("lesson_02/results", "slope_hw.png", "lesson_02/slope_hw.png"),
    fig("lesson_02/results", "slope_hw_diff_l0.png", "lesson_02/slope_hw_diff.png"),
    fig("lesson_02/results", "bias_0.5tx_diff_l0.png", "lesson_02/bias_0.5tx_diff.png"),
    fig("lesson_02/results", "bias_64tx_diff_l0.png", "lesson_02/bias_64tx_diff.png"),
    fig("lesson_02/contact", "constant_lwjgl_diff_l0.png", "lesson_02/contact_constant_lwjgl_diff.png"),
    fig("lesson_02/grazing_89", "slope_unclamped_visibility_l0.png", "lesson_02/grazing_89_slope_unclamped_visibility.png"),
    fig("lesson_02/grazing_89", "slope_shader_visibility_l0.png", "lesson_02/grazing_89_slope_shader_visibility.png"),
    fig("lesson_02/grazing_89", "slope_hw_visibility_l0.png", "lesson_02/grazing_89_slope_hw_visibility.png"),
    fig("lesson_02/thin_plate", "front_cull_diff_l0.png", "lesson_02/thin_plate_front_cull_diff.png"),
    fig("lesson_02/spot_wide", "constant_lwjgl_diff_l0.png", "lesson_02/spot_wide_constant_lwjgl_diff.png"),
    fig("lesson_03/closeup", "pcf_1x1.png", "lesson_03/closeup_pcf_1x1.png"),
    fig("lesson_03/closeup", "pcf_3x3.png", "lesson_03/closeup_pcf_3x3.png"),
    fig("lesson_03/closeup", "pcf_7x7.png", "lesson_03/closeup_pcf_7x7.png"),
    fig("lesson_03/closeup", "pcf_7x7_flat.png", "lesson_03/closeup_pcf_7x7_flat.png"),
    fig("lesson_03/closeup", "hw_2x2.png", "lesson_03/closeup_hw_2x2.png"),
    fig("lesson_03/closeup", "poisson_16.png", "lesson_03/closeup_poisson_16.png"),
    fig("lesson_03/closeup", "depth_avg_3x3.png", "lesson_03/closeup_depth_avg_3x3.png"),
    fig(
        "lesson_03/closeup",
        "depth_avg_3x3_diff_l0.png",
        "lesson_03/closeup_depth_avg_3x3_diff_l0.png",
    ),
    fig("lesson_04/results", "linear_1024.png", "lesson_04/linear_1024.png"),
    fig("lesson_04/results", "linear_1024_cube_map.png", "lesson_04/linear_1024_cube_map.png"),
    fig("lesson_04/seams", "linear_1024.png", "lesson_04/seams_linear_1024.png"),
    fig("lesson_04/seams", "depth_euclid_1024_diff_l0.png", "lesson_04/seams_depth_euclid_1024_diff.png"),
    fig("lesson_04/near_caster", "linear_1024.png", "lesson_04/near_caster_unclipped.png"),
    fig("lesson_04/near_caster", "clipped_1024.png", "lesson_04/near_caster_clipped.png"),
    fig("lesson_04/beyond_range", "linear_1024_visibility_l0.png", "lesson_04/beyond_range_clamped_visibility.png"),
    fig("lesson_04/beyond_range", "no_range_clamp_1024_visibility_l0.png", "lesson_04/beyond_range_naive_visibility.png"),
    fig("lesson_05/results", "zpass_quads.png", "lesson_05/zpass_quads.png"),
    fig("lesson_05/eye_in_umbra", "zpass_quads.png", "lesson_05/eye_in_umbra_zpass.png"),
    fig("lesson_05/eye_in_umbra", "zpass_quads_diff_l0.png", "lesson_05/eye_in_umbra_zpass_diff.png"),
    fig("lesson_06/results", "zfail_quads.png", "lesson_06/zfail_quads.png"),
    fig("lesson_06/results", "zpass_quads_diff_l0.png", "lesson_06/zpass_quads_diff_l0.png"),
    fig("lesson_06/results", "zfail_quads_diff_l0.png", "lesson_06/zfail_quads_diff_l0.png"),
    fig("lesson_06/results", "zfail_no_front_cap_diff_l0.png", "lesson_06/zfail_no_front_cap_diff_l0.png"),
    fig("lesson_06/results", "zfail_no_back_cap_diff_l0.png", "lesson_06/zfail_no_back_cap_diff_l0.png"),
    fig("lesson_06/finite_far_open", "zfail_quads.png", "lesson_06/finite_far_open_zfail_quads.png"),
    fig("lesson_06/finite_far_open", "zfail_quads_diff_l0.png", "lesson_06/finite_far_open_zfail_quads_diff_l0.png"),
    fig("lesson_06/finite_far_open", "zpass_quads_diff_l0.png", "lesson_06/finite_far_open_zpass_quads_diff_l0.png"),
    fig("lesson_07/results", "neither.png", "lesson_07/neither.png"),
    fig("lesson_07/results", "neither_diff_l1.png", "lesson_07/neither_diff_l1.png"),
    fig("lesson_07/results", "infinite.png", "lesson_07/infinite.png"),
    fig("lesson_07/results", "depth_precision.svg", "lesson_07/depth_precision.svg"),
    fig("lesson_07/results", "depth_precision.png", "lesson_07/depth_precision.png"),
    fig("lesson_07/deep_range", "infinite.png", "lesson_07/deep_range_infinite.png"),
    fig("lesson_07/deep_range", "reversed_z.png", "lesson_07/deep_range_reversed_z.png"),
    fig("lesson_07/deep_range", "infinite_diff_l1.png", "lesson_07/deep_range_infinite_diff_l1.png"),
    fig("lesson_07/deep_range", "reversed_z_diff_l1.png", "lesson_07/deep_range_reversed_z_diff_l1.png"),
    fig("lesson_08/results", "bounds_scissor.png", "lesson_08/bounds_scissor.png"),
    fig("lesson_08/results", "bounds_scissor_visibility_l3.png", "lesson_08/bounds_scissor_visibility_l3.png"),
    fig("lesson_08/results", "reference_visibility_l3.png", "lesson_08/reference_visibility_l3.png"),
    fig("lesson_09/results", "k4_cascades.png", "lesson_09/k4_cascades.png"),
    fig("lesson_09/results", "single_2048_diff_l0.png", "lesson_09/single_2048_diff.png"),
    fig("lesson_09/results", "k4_diff_l0.png", "lesson_09/k4_diff.png"),
    fig("lesson_09/results", "k4_shimmer_over.png", "lesson_09/k4_shimmer.png"),
    fig("lesson_09/results", "k4_aabb_nosnap_shimmer_over.png", "lesson_09/k4_aabb_nosnap_shimmer.png"),
    fig("lesson_10/results", "pcss.png", "lesson_10/pcss.png"),
    fig("lesson_10/results", "reference_visibility_l0.png", "lesson_10/reference_visibility_l0.png"),
    fig("lesson_10/results", "pcss_visibility_l0.png", "lesson_10/pcss_visibility_l0.png"),
    fig("lesson_10/results", "pcf_wide_16_visibility_l0.png", "lesson_10/pcf_wide_16_visibility_l0.png"),
    fig("lesson_10/results", "vsm_visibility_l0.png", "lesson_10/vsm_visibility_l0.png"),
    fig("lesson_10/results", "evsm_visibility_l0.png", "lesson_10/evsm_visibility_l0.png"),
    fig("lesson_10/results", "pcss_diff_l0.png", "lesson_10/pcss_diff_l0.png"),
    fig("lesson_10/results", "pcss_dv_l0.png", "lesson_10/pcss_dv_l0.png"),
    fig("lesson_10/results", "vsm_dv_l0.png", "lesson_10/vsm_dv_l0.png"),
    fig("lesson_10/thin", "vsm_visibility_l0.png", "lesson_10/thin_vsm.png"),
    fig("lesson_10/thin", "vsm_bleed_cut_visibility_l0.png", "lesson_10/thin_vsm_bleed_cut.png"),
    fig("lesson_10/thin", "vsm_dv_l0.png", "lesson_10/thin_vsm_dv.png"),
    fig("lesson_10/contact", "pcss_visibility_l0.png", "lesson_10/contact_pcss_visibility_l0.png"),
    fig("lesson_10/contact", "pcf_wide_16_visibility_l0.png", "lesson_10/contact_pcf_wide_16_visibility_l0.png"),
    fig("lesson_10/contact", "reference_visibility_l0.png", "lesson_10/contact_reference_visibility_l0.png"),
];

/// Text files a run writes that the book includes as they are (measured
/// tables a lesson makes itself): `file` of `run`, copied to
/// `book/src/generated/<dest>`. The drift test compares them byte for byte.
pub const TEXTS: &[Figure] = &[fig(
    "lesson_07/results",
    "depth_precision.md",
    "lesson_07/depth_precision.md",
)];

/// The closing chapter's families: which lessons each one is.
pub const FAMILIES: &[(&str, &[&str])] = &[
    (
        "shadow maps",
        &["lesson_01", "lesson_02", "lesson_03", "lesson_04"],
    ),
    (
        "shadow volumes",
        &["lesson_05", "lesson_06", "lesson_07", "lesson_08"],
    ),
    ("cascaded shadow maps", &["lesson_09"]),
    ("soft shadows", &["lesson_10"]),
];

/// A renderer's documented default, measured as a variant of our lesson,
/// and the variant of ours it is compared with. The variant's doc comment
/// cites the source.
#[derive(Clone, Copy, Debug)]
pub struct Peer {
    pub lesson: &'static str,
    pub variant: &'static str,
    pub ours: &'static str,
    pub who: &'static str,
}

const fn peer(
    lesson: &'static str,
    variant: &'static str,
    ours: &'static str,
    who: &'static str,
) -> Peer {
    Peer {
        lesson,
        variant,
        ours,
        who,
    }
}

/// The peers' defaults beside ours (chapter "Choosing a technique").
#[rustfmt::skip]
pub const PEERS: &[Peer] = &[
    peer("lesson_02", "constant_lwjgl", "slope_hw", "the lwjgl book's (legacy edition) constant bias"),
    peer("lesson_02", "learnopengl", "slope_hw", "LearnOpenGL's slope bias"),
    peer("lesson_02", "wgpu_example", "slope_hw", "the wgpu shadow example's hardware bias"),
    peer("lesson_02", "bevy_bias", "slope_hw", "Bevy's directional depth + normal bias"),
    peer("lesson_03", "learnopengl_pcf", "poisson_16", "LearnOpenGL's bias + 3×3 PCF"),
    peer("lesson_03", "wgpu_example_hw2x2", "poisson_16", "the wgpu shadow example's bias + hardware 2×2"),
    peer("lesson_03", "bevy", "poisson_16", "Bevy's directional defaults"),
    peer("lesson_04", "learnopengl_1tap", "pcf3d_1024", "LearnOpenGL's point shadow, one tap"),
    peer("lesson_04", "learnopengl_pcf20", "pcf3d_1024", "LearnOpenGL's 20-tap point kernel"),
    peer("lesson_04", "bevy_point", "pcf3d_1024", "Bevy's point-light biases"),
    peer("lesson_10", "filament_pcf", "pcss", "Filament's PCF (its default)"),
    peer("lesson_10", "filament_pcss", "pcss", "Filament's PCSS (an option)"),
    peer("lesson_10", "filament_evsm", "pcss", "Filament's VSM, an EVSM (an option)"),
    peer("lesson_10", "bevy_gaussian", "pcss", "Bevy's Gaussian PCF (its default)"),
    peer("lesson_10", "bevy_pcss_or_pcf", "pcss", "Bevy's PCSS on a spot (an option), its default on a sun"),
    peer("lesson_10", "godot_pcf", "pcss", "Godot's PCF (its default)"),
    peer("lesson_10", "godot_soft_low", "pcss", "Godot's soft shadow at Soft Low (an option)"),
    peer("lesson_10", "threejs_pcf", "pcss", "three.js's PCFShadowMap (its default)"),
    peer("lesson_10", "threejs_pcf_soft", "pcss", "three.js's PCFSoftShadowMap (an option, deprecated in r182)"),
    peer("lesson_10", "threejs_vsm", "pcss", "three.js's VSMShadowMap (an option)"),
];

/// The runs and variants of the volume-building table: (run id, [(variant,
/// the pass that tests the edges)]).
#[rustfmt::skip]
pub const VOLUME_BUILDS: &[(&str, &[(&str, &str)])] = &[
    ("lesson_05/results", &[("zpass_cpu", "cpu_silhouette"), ("zpass_quads", "volume"), ("zpass_compute", "extrude")]),
    ("lesson_05/dense", &[("zpass_cpu", "cpu_silhouette"), ("zpass_quads", "volume"), ("zpass_compute", "extrude")]),
    ("lesson_05/holed", &[("zpass_cpu", "cpu_silhouette"), ("zpass_quads", "volume"), ("zpass_compute", "extrude")]),
];
