//! What every column of a generated table means, written under the table
//! where it is read. The standard columns, every counter a lesson reports
//! and every timed pass are defined here once, in the order the tables
//! show them (what a technique gets wrong, then what it does, in the order
//! the frame does it, then what it costs). A table whose writer has columns
//! of its own passes their definitions with [`legend_with`].
//!
//! `tests/book_legends.rs` reads every generated table and fails when a
//! column has no entry in the legend under it.

use anyhow::{bail, Result};

/// The standard columns of a run's tables.
const STANDARD: &[(&str, &str)] = &[
    ("variant", "the lesson's variant (its `--variant` name); each chapter's variants listing says what it changes"),
    ("scene", "the scene file the row was run on"),
    ("misclassified %", "the receiver pixels classified differently from the exact reference (lit where V ≥ ½), in % of the receiver pixels of every light"),
    ("false shadow %", "the receiver pixels shadowed here but lit in the reference (acne, over-long shadows), in % of the receiver pixels"),
    ("false lit %", "the receiver pixels lit here but shadowed in the reference (light leaks, Peter Panning), in % of the receiver pixels"),
    ("mean \\|ΔV\\| %", "the mean of |V − V_ref| over the receiver pixels, in %: it sees partial visibility (a penumbra, a blend) that misclassified % rounds away"),
    ("penumbra \\|ΔV\\| %", "a light with a size (a soft shadow): the mean of |V − V_ref| over the receiver pixels in the exact reference's penumbra (0 < V_ref < 1), in %: how far the penumbra's shade is from the visible fraction of the emitter; — where the variant reports none"),
    ("bleeding %", "a light with a size: of the receiver pixels in the exact reference's umbra (V_ref = 0, the emitter wholly hidden), the share the variant lights above V = 0.1, in %; near the umbra's rim this is mostly a blur's spill, light through a blocker (the variance maps' bleeding) is the classes table's leak %; 0 where the scene has no umbra"),
    ("frame ms", "the frame's wall-clock cost, from the start of recording to the GPU's completion: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("GPU ms", "the GPU's time for the whole frame, from its timestamps: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("CPU ms", "the CPU's time to record and submit the frame, waits for the GPU left out: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("shadows cost (frame, vs no shadows)", "the frame's median over the no-shadow baseline's, when their spreads do not overlap (× the ratio); else no measurable difference"),
    ("vs the fastest", "the frame's median over the fastest variant's, when their spreads do not overlap; else no measurable difference"),
];

/// Every counter a lesson reports, in the order the tables show them:
/// the map or the volumes first, then what the frame draws, then checks.
pub const COUNTERS: &[(&str, &str)] = &[
    // Shadow maps.
    ("shadow_map_size", "the shadow map's side, in texels (a cube map: one face's side)"),
    ("cascades", "the number of cascades (shadow maps split along the view)"),
    ("texel_um_u", "one shadow-map texel's width in the scene, in micrometres"),
    ("texel_um_v", "one shadow-map texel's height in the scene, in micrometres"),
    ("texels_per_100m_at_2m", "shadow-map texels per 100 m of scene, in the cascade that holds view depth 2 m"),
    ("texels_per_100m_at_10m", "shadow-map texels per 100 m of scene, in the cascade that holds view depth 10 m"),
    ("texels_per_100m_at_50m", "shadow-map texels per 100 m of scene, in the cascade that holds view depth 50 m"),
    ("texels_per_100m_at_200m", "shadow-map texels per 100 m of scene, in the cascade that holds view depth 200 m"),
    ("origin_off_grid_millitexels", "how far the cascades' light-space origins lie off their texel grids, worst cascade, in thousandths of a texel: 0 when snapped"),
    ("near_plane_mm", "the cube map's near plane, in millimetres"),
    ("unclipped_depth", "1 where the pass clamps depth instead of clipping it (`unclipped_depth`), else 0"),
    ("slope_bias_millitexels", "the slope-scaled bias, in thousandths of a texel per unit of tan θ"),
    ("faces_rendered", "cube-map faces drawn into, over all lights"),
    ("caster_draws", "caster draw calls into the shadow maps (one per caster and face it can touch)"),
    ("shadow_fragments", "fragments the shadow pass rasterised, every map, face and cascade"),
    ("shadow_texels_written", "shadow-map texels that pass's fragments wrote (depth test passed)"),
    ("shadow_texels_scissored", "cube-face texels inside the faces' scissor rectangles, the texels a visible receiver's lookup can read (lesson 04's `face_rects`); a whole face where there is no rectangle"),
    ("taps", "depth comparisons per shadow lookup"),
    ("blocker_search_taps", "the blocker search's depth reads per pixel and light, one texel each, before the filter (PCSS's first step; a pixel whose search finds no blocker stops there); 0 for a fixed filter or a variance map"),
    ("filter_taps_per_pixel", "depth comparisons the lit pass makes per pixel and light"),
    ("texels_read", "shadow-map texels one lookup reads (a bilinear comparison reads 2×2)"),
    ("probed_pixels", "an adaptive filter's pixels: those its lit pass shaded inside the map, where its 4 probes ran (counted in one untimed draw)"),
    ("full_disk_pixels", "of those, the pixels whose probes disagreed and that took the full disk"),
    ("filter_taps", "the depth comparisons an adaptive filter made over the frame: 4 per probed pixel, 16 more per full-disk pixel"),
    // Shadow volumes: the casters, their meshes and silhouettes.
    ("casters_drawn", "caster-light pairs whose shadow volume is drawn"),
    ("casters_zpass", "caster-light pairs counted with z-pass (their volumes cannot reach the near plane)"),
    ("casters_zfail", "caster-light pairs counted with z-fail, with caps"),
    ("casters_skipped", "caster-light pairs left out: their volumes cannot change a visible pixel"),
    ("open_edges", "caster mesh edges with one face (the mesh is open there), summed over the casters; the lesson draws such casters two-sided"),
    ("nonmanifold_edges", "caster mesh edges with three or more faces, summed over the casters"),
    ("degenerate_triangles", "zero-area triangles of the casters' own meshes (the input, not the volumes), summed over the casters; they face no light and are left out"),
    ("edges_tested", "caster edges tested for the silhouette, per frame over all lights (on the CPU or in a shader)"),
    ("silhouette_edges", "silhouette edges found and extruded, per frame over all lights (— where the route extrudes on the fly)"),
    ("volume_triangles", "triangles submitted for the shadow volumes (sides and caps); the quads route sends every edge, most of them zero-area"),
    ("max_volume_overlap", "the most shadow volumes any sampled point lies in (a grid of pixels); 256 wraps an 8-bit stencil to 0"),
    // Bounds (lesson 08).
    ("lights_around_camera", "lights whose range sphere holds the camera"),
    ("lights_crossing_near_plane", "lights whose range sphere crosses the near plane without holding the camera"),
    ("lights_culled", "lights whose range sphere is off screen, so nothing of theirs is drawn"),
    ("scissor_pixels", "pixels inside the lights' scissor rectangles, summed over the lights (the whole screen per light without a scissor)"),
    // What the frame rasterises.
    ("volume_fragments", "shadow-volume fragments rasterised (an exact, untimed tally of the volume pass)"),
    ("stencil_fragments", "of the volume fragments, those that pass the depth-bounds mark and reach the stencil"),
    ("stencil_updates", "of those, the fragments that change the stencil (z-pass: in front of the surface; z-fail: behind it)"),
    ("fragment_shader_invocations", "the adapter's pipeline statistic for a copy of the volume pass (llvmpipe counts 16 per 4×4 block it shades, so it is not a fragment count there)"),
    ("draws", "draw calls in the frame, every pass"),
    // Precision (lesson 07).
    ("depth_gap_ppb_at_half_far", "the smallest relative depth gap Δd/d the depth buffer resolves at half the far distance, in parts per billion (10⁹: nothing resolved)"),
    ("depth_gap_ppb_at_sqrt_near_far", "the same at √(near · far), in parts per billion"),
];

/// The timed passes of a frame (the passes tables' columns, `` `name` ms ``).
pub const PASSES: &[(&str, &str)] = &[
    (
        "base",
        "the base pass: the scene's depth and colour, with no shadow",
    ),
    (
        "shadow",
        "the shadow-map passes: every map, face and cascade",
    ),
    (
        "extrude",
        "the compute pass that finds silhouettes and writes the volumes",
    ),
    (
        "volume",
        "the shadow-volume pass into the stencil (and the bounds marks)",
    ),
    (
        "moments",
        "the compute pass that turns the depth map into moments (a variance map) and blurs them along x",
    ),
    (
        "blur",
        "the compute pass that blurs the moments again, along y",
    ),
    (
        "min_max",
        "the compute passes that build the map's min/max mip chain, one a level (`pcss_min_max`)",
    ),
    ("lighting", "the lit passes, one per light"),
    (
        "cpu_silhouette",
        "CPU time finding silhouettes and building the volumes",
    ),
    (
        "cpu_bounds",
        "CPU time computing the lights' range-sphere bounds",
    ),
    (
        "cpu_camera",
        "CPU time fitting a variant's own camera and uploading it",
    ),
    (
        "cpu_fit",
        "CPU time fitting the cascades to the view and uploading them",
    ),
    (
        "cpu_cull",
        "CPU time choosing, per cascade, the casters that can shadow its receivers and their scissor rectangles",
    ),
    (
        "cpu_record",
        "CPU time recording the frame's passes (wgpu's encoders)",
    ),
    ("cpu_total", "the CPU's time to record and submit the frame"),
    (
        "frame",
        "the frame's wall-clock cost, start of recording to GPU completion",
    ),
];

/// The rank of a counter in [`COUNTERS`] (unknown ones last, by name).
pub fn counter_rank(name: &str) -> (usize, String) {
    let i = COUNTERS.iter().position(|(n, _)| *n == name);
    (i.unwrap_or(usize::MAX), name.to_string())
}

/// The rank of a pass in [`PASSES`].
pub fn pass_rank(name: &str) -> (usize, String) {
    let i = PASSES.iter().position(|(n, _)| *n == name);
    (i.unwrap_or(usize::MAX), name.to_string())
}

/// The definition of a standard column, a counter (`` `name` ``) or a
/// pass (`` `name` ms ``).
fn definition(column: &str) -> Option<String> {
    if let Some((_, d)) = STANDARD.iter().find(|(n, _)| *n == column) {
        return Some(d.to_string());
    }
    let code = column.strip_prefix('`')?;
    if let Some(name) = code.strip_suffix("` ms") {
        return PASSES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, d)| format!("{d}: median [spread], ms"));
    }
    let name = code.strip_suffix('`')?;
    COUNTERS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, d)| d.to_string())
}

/// The legend of a table whose writer defines its own columns (`own`),
/// the others taken from the standard ones. A column defined nowhere gets
/// an empty entry, which `tests/book_legends.rs` reports.
pub fn legend_own(columns: &[String], own: &[(&str, &str)]) -> String {
    details(&definitions(columns, own))
}

/// The legend of a table with `columns`: every column defined, in order.
pub fn legend(columns: &[String]) -> Result<String> {
    legend_with(columns, &[])
}

/// The legend, with the definitions of a table's own columns (`own`) taking
/// precedence over the standard ones.
pub fn legend_with(columns: &[String], own: &[(&str, &str)]) -> Result<String> {
    let defined = definitions(columns, own);
    if let Some((c, _)) = defined.iter().find(|(_, d)| d.is_none()) {
        bail!("the column {c:?} has no definition: add it to book/generate/legend.rs");
    }
    Ok(details(&defined))
}

/// Each column with its definition: the table's own (`own`) first, then
/// the standard one; `None` where neither defines it.
fn definitions<'a>(
    columns: &'a [String],
    own: &[(&str, &str)],
) -> Vec<(&'a String, Option<String>)> {
    let own_definition = |c: &String| own.iter().find(|(n, _)| *n == c.as_str());
    (columns.iter())
        .map(|c| {
            let d = own_definition(c).map(|(_, d)| d.to_string());
            (c, d.or_else(|| definition(c)))
        })
        .collect()
}

/// The legend block: one `- column: definition` line a column (empty
/// where it has none), folded under "What each column means".
fn details(defined: &[(&String, Option<String>)]) -> String {
    let mut s = String::from("\n<details><summary>What each column means</summary>\n\n");
    for (c, d) in defined {
        let d = d.as_deref().unwrap_or_default();
        s += &format!("- {c}: {d}\n");
    }
    s += "\n</details>\n";
    s
}
