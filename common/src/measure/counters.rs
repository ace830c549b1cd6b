//! The counters a lesson reports: one definition of each (its name in
//! the report, its unit, the legend the book's tables print under its
//! column), used by the lessons, the runner, the snapshots, the grader and
//! the book's generator. A lesson fills a [`Counts`] keyed by these
//! constants, so a renamed or misspelt counter does not compile;
//! `tests/counter_names.rs` checks that no other file spells a counter's name as a
//! string literal.
//!
//! [`ALL`] is the order the book's tables show them: the map or the
//! volumes first, then what the frame draws, then checks.

use std::collections::BTreeMap;

/// One counter: deterministic, the same on every run of a scene on one
/// adapter (unlike a time).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Counter {
    /// Its key in `report.json`'s `counters` and its table column.
    pub name: &'static str,
    /// What one unit of it is ("draw calls", "texels", "µm").
    pub unit: &'static str,
    /// What it counts, in one sentence: the legend under a table's column.
    pub legend: &'static str,
}

impl Counter {
    /// The counter named `name`, if there is one.
    pub fn named(name: &str) -> Option<Counter> {
        ALL.iter().copied().find(|c| c.name == name)
    }
}

impl std::fmt::Display for Counter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// What a lesson counted for a variant: each counter at most once, in the
/// report's order (by name).
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(transparent)]
pub struct Counts(BTreeMap<&'static str, u64>);

impl Counts {
    /// No counts.
    pub fn new() -> Counts {
        Counts::default()
    }

    /// Sets `counter` to `n`.
    pub fn set(&mut self, counter: Counter, n: u64) {
        self.0.insert(counter.name, n);
    }

    /// Adds `n` to `counter` (from 0 where it is not set).
    pub fn add(&mut self, counter: Counter, n: u64) {
        *self.0.entry(counter.name).or_insert(0) += n;
    }

    /// `counter`'s value, if it was counted.
    pub fn get(&self, counter: Counter) -> Option<u64> {
        self.0.get(counter.name).copied()
    }

    /// Every count of `other` into `self`, replacing the same counters.
    pub fn extend(&mut self, other: &Counts) {
        self.0.extend(other.0.iter().map(|(k, v)| (*k, *v)));
    }

    /// Whether nothing was counted.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The counts as the report writes them: name to value.
    pub fn to_report(&self) -> BTreeMap<String, u64> {
        self.0.iter().map(|(k, v)| (k.to_string(), *v)).collect()
    }
}

impl<const N: usize> From<[(Counter, u64); N]> for Counts {
    fn from(counts: [(Counter, u64); N]) -> Counts {
        let mut c = Counts::new();
        for (counter, n) in counts {
            c.set(counter, n);
        }
        c
    }
}

/// Every counter, in the order the book's tables show them.
pub const ALL: &[Counter] = &[
    SHADOW_MAP_SIZE,
    CASCADES,
    TEXEL_UM_U,
    TEXEL_UM_V,
    TEXELS_PER_100M_AT_2M,
    TEXELS_PER_100M_AT_10M,
    TEXELS_PER_100M_AT_50M,
    TEXELS_PER_100M_AT_200M,
    ORIGIN_OFF_GRID_MILLITEXELS,
    NEAR_PLANE_MM,
    UNCLIPPED_DEPTH,
    SLOPE_BIAS_MILLITEXELS,
    FACES_RENDERED,
    CASTER_DRAWS,
    SHADOW_FRAGMENTS,
    SHADOW_TEXELS_WRITTEN,
    SHADOW_TEXELS_SCISSORED,
    TAPS,
    BLOCKER_SEARCH_TAPS,
    FILTER_TAPS_PER_PIXEL,
    TEXELS_READ,
    PROBED_PIXELS,
    FULL_DISK_PIXELS,
    FILTER_TAPS,
    CASTERS_DRAWN,
    CASTERS_ZPASS,
    CASTERS_ZFAIL,
    CASTERS_SKIPPED,
    OPEN_EDGES,
    NONMANIFOLD_EDGES,
    DEGENERATE_TRIANGLES,
    EDGES_TESTED,
    SILHOUETTE_EDGES,
    VOLUME_TRIANGLES,
    MAX_VOLUME_OVERLAP,
    LIGHTS_AROUND_CAMERA,
    LIGHTS_CROSSING_NEAR_PLANE,
    LIGHTS_CULLED,
    SCISSOR_PIXELS,
    VOLUME_FRAGMENTS,
    STENCIL_FRAGMENTS,
    STENCIL_UPDATES,
    FRAGMENT_SHADER_INVOCATIONS,
    DRAWS,
    DEPTH_GAP_PPB_AT_HALF_FAR,
    DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR,
    VERTICES_BEFORE_NEAR,
];

// Shadow maps.
/// `shadow_map_size`, in texels: the shadow map's side, in texels (a cube map: one face's side).
pub const SHADOW_MAP_SIZE: Counter = Counter {
    name: "shadow_map_size",
    unit: "texels",
    legend: "the shadow map's side, in texels (a cube map: one face's side)",
};
/// `cascades`, in cascades: the number of cascades (shadow maps split along the view).
pub const CASCADES: Counter = Counter {
    name: "cascades",
    unit: "cascades",
    legend: "the number of cascades (shadow maps split along the view)",
};
/// `texel_um_u`, in µm: one shadow-map texel's width in the scene, in micrometres.
pub const TEXEL_UM_U: Counter = Counter {
    name: "texel_um_u",
    unit: "µm",
    legend: "one shadow-map texel's width in the scene, in micrometres",
};
/// `texel_um_v`, in µm: one shadow-map texel's height in the scene, in micrometres.
pub const TEXEL_UM_V: Counter = Counter {
    name: "texel_um_v",
    unit: "µm",
    legend: "one shadow-map texel's height in the scene, in micrometres",
};
/// `texels_per_100m_at_2m`, in texels per 100 m: shadow-map texels per 100 m of scene, in the cascade that holds view depth 2 m.
pub const TEXELS_PER_100M_AT_2M: Counter = Counter {
    name: "texels_per_100m_at_2m",
    unit: "texels per 100 m",
    legend: "shadow-map texels per 100 m of scene, in the cascade that holds view depth 2 m",
};
/// `texels_per_100m_at_10m`, in texels per 100 m: shadow-map texels per 100 m of scene, in the cascade that holds view depth 10 m.
pub const TEXELS_PER_100M_AT_10M: Counter = Counter {
    name: "texels_per_100m_at_10m",
    unit: "texels per 100 m",
    legend: "shadow-map texels per 100 m of scene, in the cascade that holds view depth 10 m",
};
/// `texels_per_100m_at_50m`, in texels per 100 m: shadow-map texels per 100 m of scene, in the cascade that holds view depth 50 m.
pub const TEXELS_PER_100M_AT_50M: Counter = Counter {
    name: "texels_per_100m_at_50m",
    unit: "texels per 100 m",
    legend: "shadow-map texels per 100 m of scene, in the cascade that holds view depth 50 m",
};
/// `texels_per_100m_at_200m`, in texels per 100 m: shadow-map texels per 100 m of scene, in the cascade that holds view depth 200 m.
pub const TEXELS_PER_100M_AT_200M: Counter = Counter {
    name: "texels_per_100m_at_200m",
    unit: "texels per 100 m",
    legend: "shadow-map texels per 100 m of scene, in the cascade that holds view depth 200 m",
};
/// `origin_off_grid_millitexels`, in millitexels: how far the cascades' light-space origins lie off their texel grids, worst cascade, in thousandths of a texel: 0 when snapped.
pub const ORIGIN_OFF_GRID_MILLITEXELS: Counter = Counter {
    name: "origin_off_grid_millitexels",
    unit: "millitexels",
    legend: "how far the cascades' light-space origins lie off their texel grids, worst cascade, in thousandths of a texel: 0 when snapped",
};
/// `near_plane_mm`, in mm: the cube map's near plane, in millimetres.
pub const NEAR_PLANE_MM: Counter = Counter {
    name: "near_plane_mm",
    unit: "mm",
    legend: "the cube map's near plane, in millimetres",
};
/// `unclipped_depth`, in 0 or 1: 1 where the pass clamps depth instead of clipping it (`unclipped_depth`), else 0.
pub const UNCLIPPED_DEPTH: Counter = Counter {
    name: "unclipped_depth",
    unit: "0 or 1",
    legend: "1 where the pass clamps depth instead of clipping it (`unclipped_depth`), else 0",
};
/// `slope_bias_millitexels`, in millitexels per unit of tan θ: the slope-scaled bias, in thousandths of a texel per unit of tan θ.
pub const SLOPE_BIAS_MILLITEXELS: Counter = Counter {
    name: "slope_bias_millitexels",
    unit: "millitexels per unit of tan θ",
    legend: "the slope-scaled bias, in thousandths of a texel per unit of tan θ",
};
/// `faces_rendered`, in faces: cube-map faces drawn into, over all lights.
pub const FACES_RENDERED: Counter = Counter {
    name: "faces_rendered",
    unit: "faces",
    legend: "cube-map faces drawn into, over all lights",
};
/// `caster_draws`, in draw calls: caster draw calls into the shadow maps (one per caster and face it can touch).
pub const CASTER_DRAWS: Counter = Counter {
    name: "caster_draws",
    unit: "draw calls",
    legend: "caster draw calls into the shadow maps (one per caster and face it can touch)",
};
/// `shadow_fragments`, in fragments: fragments the shadow pass rasterised, every map, face and cascade.
pub const SHADOW_FRAGMENTS: Counter = Counter {
    name: "shadow_fragments",
    unit: "fragments",
    legend: "fragments the shadow pass rasterised, every map, face and cascade",
};
/// `shadow_texels_written`, in texels: shadow-map texels that pass's fragments wrote (depth test passed).
pub const SHADOW_TEXELS_WRITTEN: Counter = Counter {
    name: "shadow_texels_written",
    unit: "texels",
    legend: "shadow-map texels that pass's fragments wrote (depth test passed)",
};
/// `shadow_texels_scissored`, in texels: cube-face texels inside the faces' scissor rectangles, the texels a visible receiver's lookup can read (lesson 04's `face_rects`); a whole face where there is no rectangle.
pub const SHADOW_TEXELS_SCISSORED: Counter = Counter {
    name: "shadow_texels_scissored",
    unit: "texels",
    legend: "cube-face texels inside the faces' scissor rectangles, the texels a visible receiver's lookup can read (lesson 04's `face_rects`); a whole face where there is no rectangle",
};
/// `taps`, in comparisons per lookup: depth comparisons per shadow lookup.
pub const TAPS: Counter = Counter {
    name: "taps",
    unit: "comparisons per lookup",
    legend: "depth comparisons per shadow lookup",
};
/// `blocker_search_taps`, in depth reads per pixel and light: the blocker search's depth reads per pixel and light, one texel each, before the filter (PCSS's first step; a pixel whose search finds no blocker stops there); 0 for a fixed filter or a variance map.
pub const BLOCKER_SEARCH_TAPS: Counter = Counter {
    name: "blocker_search_taps",
    unit: "depth reads per pixel and light",
    legend: "the blocker search's depth reads per pixel and light, one texel each, before the filter (PCSS's first step; a pixel whose search finds no blocker stops there); 0 for a fixed filter or a variance map",
};
/// `filter_taps_per_pixel`, in comparisons per pixel and light: depth comparisons the lit pass makes per pixel and light.
pub const FILTER_TAPS_PER_PIXEL: Counter = Counter {
    name: "filter_taps_per_pixel",
    unit: "comparisons per pixel and light",
    legend: "depth comparisons the lit pass makes per pixel and light",
};
/// `texels_read`, in texels per lookup: shadow-map texels one lookup reads (a bilinear comparison reads 2×2).
pub const TEXELS_READ: Counter = Counter {
    name: "texels_read",
    unit: "texels per lookup",
    legend: "shadow-map texels one lookup reads (a bilinear comparison reads 2×2)",
};
/// `probed_pixels`, in pixels: an adaptive filter's pixels: those its lit pass shaded inside the map, where its 4 probes ran (counted in one untimed draw).
pub const PROBED_PIXELS: Counter = Counter {
    name: "probed_pixels",
    unit: "pixels",
    legend: "an adaptive filter's pixels: those its lit pass shaded inside the map, where its 4 probes ran (counted in one untimed draw)",
};
/// `full_disk_pixels`, in pixels: of those, the pixels whose probes disagreed and that took the full disk.
pub const FULL_DISK_PIXELS: Counter = Counter {
    name: "full_disk_pixels",
    unit: "pixels",
    legend: "of those, the pixels whose probes disagreed and that took the full disk",
};
/// `filter_taps`, in comparisons: the depth comparisons an adaptive filter made over the frame: 4 per probed pixel, 16 more per full-disk pixel.
pub const FILTER_TAPS: Counter = Counter {
    name: "filter_taps",
    unit: "comparisons",
    legend: "the depth comparisons an adaptive filter made over the frame: 4 per probed pixel, 16 more per full-disk pixel",
};

// Shadow volumes: the casters, their meshes and silhouettes.
/// `casters_drawn`, in caster-light pairs: caster-light pairs whose shadow volume is drawn.
pub const CASTERS_DRAWN: Counter = Counter {
    name: "casters_drawn",
    unit: "caster-light pairs",
    legend: "caster-light pairs whose shadow volume is drawn",
};
/// `casters_zpass`, in caster-light pairs: caster-light pairs counted with z-pass (their volumes cannot reach the near plane).
pub const CASTERS_ZPASS: Counter = Counter {
    name: "casters_zpass",
    unit: "caster-light pairs",
    legend: "caster-light pairs counted with z-pass (their volumes cannot reach the near plane)",
};
/// `casters_zfail`, in caster-light pairs: caster-light pairs counted with z-fail, with caps.
pub const CASTERS_ZFAIL: Counter = Counter {
    name: "casters_zfail",
    unit: "caster-light pairs",
    legend: "caster-light pairs counted with z-fail, with caps",
};
/// `casters_skipped`, in caster-light pairs: caster-light pairs left out: their volumes cannot change a visible pixel.
pub const CASTERS_SKIPPED: Counter = Counter {
    name: "casters_skipped",
    unit: "caster-light pairs",
    legend: "caster-light pairs left out: their volumes cannot change a visible pixel",
};
/// `open_edges`, in edges: caster mesh edges with one face (the mesh is open there), summed over the casters; the lesson draws such casters two-sided.
pub const OPEN_EDGES: Counter = Counter {
    name: "open_edges",
    unit: "edges",
    legend: "caster mesh edges with one face (the mesh is open there), summed over the casters; the lesson draws such casters two-sided",
};
/// `nonmanifold_edges`, in edges: caster mesh edges with three or more faces, summed over the casters.
pub const NONMANIFOLD_EDGES: Counter = Counter {
    name: "nonmanifold_edges",
    unit: "edges",
    legend: "caster mesh edges with three or more faces, summed over the casters",
};
/// `degenerate_triangles`, in triangles: zero-area triangles of the casters' own meshes (the input, not the volumes), summed over the casters; they face no light and are left out.
pub const DEGENERATE_TRIANGLES: Counter = Counter {
    name: "degenerate_triangles",
    unit: "triangles",
    legend: "zero-area triangles of the casters' own meshes (the input, not the volumes), summed over the casters; they face no light and are left out",
};
/// `edges_tested`, in edges per frame: caster edges tested for the silhouette, per frame over all lights (on the CPU or in a shader).
pub const EDGES_TESTED: Counter = Counter {
    name: "edges_tested",
    unit: "edges per frame",
    legend: "caster edges tested for the silhouette, per frame over all lights (on the CPU or in a shader)",
};
/// `silhouette_edges`, in edges per frame: silhouette edges found and extruded, per frame over all lights (— where the route extrudes on the fly).
pub const SILHOUETTE_EDGES: Counter = Counter {
    name: "silhouette_edges",
    unit: "edges per frame",
    legend: "silhouette edges found and extruded, per frame over all lights (— where the route extrudes on the fly)",
};
/// `volume_triangles`, in triangles: triangles submitted for the shadow volumes (sides and caps); the quads route sends every edge, most of them zero-area.
pub const VOLUME_TRIANGLES: Counter = Counter {
    name: "volume_triangles",
    unit: "triangles",
    legend: "triangles submitted for the shadow volumes (sides and caps); the quads route sends every edge, most of them zero-area",
};
/// `max_volume_overlap`, in volumes: the most shadow volumes any sampled point lies in (a grid of pixels); 256 wraps an 8-bit stencil to 0.
pub const MAX_VOLUME_OVERLAP: Counter = Counter {
    name: "max_volume_overlap",
    unit: "volumes",
    legend: "the most shadow volumes any sampled point lies in (a grid of pixels); 256 wraps an 8-bit stencil to 0",
};

// Bounds (lesson 08).
/// `lights_around_camera`, in lights: lights whose range sphere holds the camera.
pub const LIGHTS_AROUND_CAMERA: Counter = Counter {
    name: "lights_around_camera",
    unit: "lights",
    legend: "lights whose range sphere holds the camera",
};
/// `lights_crossing_near_plane`, in lights: lights whose range sphere crosses the near plane without holding the camera.
pub const LIGHTS_CROSSING_NEAR_PLANE: Counter = Counter {
    name: "lights_crossing_near_plane",
    unit: "lights",
    legend: "lights whose range sphere crosses the near plane without holding the camera",
};
/// `lights_culled`, in lights: lights whose range sphere is off screen, so nothing of theirs is drawn.
pub const LIGHTS_CULLED: Counter = Counter {
    name: "lights_culled",
    unit: "lights",
    legend: "lights whose range sphere is off screen, so nothing of theirs is drawn",
};
/// `scissor_pixels`, in pixels: pixels inside the lights' scissor rectangles, summed over the lights (the whole screen per light without a scissor).
pub const SCISSOR_PIXELS: Counter = Counter {
    name: "scissor_pixels",
    unit: "pixels",
    legend: "pixels inside the lights' scissor rectangles, summed over the lights (the whole screen per light without a scissor)",
};

// What the frame rasterises.
/// `volume_fragments`, in fragments: shadow-volume fragments rasterised (an exact, untimed tally of the volume pass).
pub const VOLUME_FRAGMENTS: Counter = Counter {
    name: "volume_fragments",
    unit: "fragments",
    legend: "shadow-volume fragments rasterised (an exact, untimed tally of the volume pass)",
};
/// `stencil_fragments`, in fragments: of the volume fragments, those that pass the depth-bounds mark and reach the stencil.
pub const STENCIL_FRAGMENTS: Counter = Counter {
    name: "stencil_fragments",
    unit: "fragments",
    legend: "of the volume fragments, those that pass the depth-bounds mark and reach the stencil",
};
/// `stencil_updates`, in fragments: of those, the fragments that change the stencil (z-pass: in front of the surface; z-fail: behind it).
pub const STENCIL_UPDATES: Counter = Counter {
    name: "stencil_updates",
    unit: "fragments",
    legend: "of those, the fragments that change the stencil (z-pass: in front of the surface; z-fail: behind it)",
};
/// `fragment_shader_invocations`, in invocations: the adapter's pipeline statistic for a copy of the volume pass (llvmpipe counts 16 per 4×4 block it shades, so it is not a fragment count there).
pub const FRAGMENT_SHADER_INVOCATIONS: Counter = Counter {
    name: "fragment_shader_invocations",
    unit: "invocations",
    legend: "the adapter's pipeline statistic for a copy of the volume pass (llvmpipe counts 16 per 4×4 block it shades, so it is not a fragment count there)",
};
/// `draws`, in draw calls: draw calls in the frame, every pass.
pub const DRAWS: Counter = Counter {
    name: "draws",
    unit: "draw calls",
    legend: "draw calls in the frame, every pass",
};

// Precision (lesson 07).
/// `depth_gap_ppb_at_half_far`, in parts per billion: the smallest relative depth gap Δd/d the depth buffer resolves at half the far distance, in parts per billion (10⁹: nothing resolved).
pub const DEPTH_GAP_PPB_AT_HALF_FAR: Counter = Counter {
    name: "depth_gap_ppb_at_half_far",
    unit: "parts per billion",
    legend: "the smallest relative depth gap Δd/d the depth buffer resolves at half the far distance, in parts per billion (10⁹: nothing resolved)",
};
/// `depth_gap_ppb_at_sqrt_near_far`, in parts per billion: the same at √(near · far), in parts per billion.
pub const DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR: Counter = Counter {
    name: "depth_gap_ppb_at_sqrt_near_far",
    unit: "parts per billion",
    legend: "the same at √(near · far), in parts per billion",
};

/// `vertices_before_near`, in vertices: scene vertices the adapted near plane clips that the scene file's near plane keeps (lesson 07's exercise).
pub const VERTICES_BEFORE_NEAR: Counter = Counter {
    name: "vertices_before_near",
    unit: "vertices",
    legend: "scene vertices the adapted near plane clips that the scene file's near plane keeps (lesson 07's exercise)",
};
