//! When each measurement on another adapter was made, on which GPU
//! ([`gpu`]), and what changed in the lessons since: a set's variant
//! changed after its commit is left out of every table that shows the set,
//! and named under it ([`changes_note`]). Read by the sets' tables
//! ([`crate::sets`]), the GPU cost tables ([`crate::gpu_costs`]), the
//! GPUs' notes ([`crate::gpus`]) and the taps' floor ([`crate::taps`]).

use std::path::Path;

use anyhow::{Context, Result};

use crate::manifest::RUNS;
use crate::record::Record;

/// The folder of the other sets, under `book/src/generated/`.
pub const SETS_DIR: &str = "sets";

/// Where and when a committed set (or another measurement of the book's
/// lessons) was made.
pub struct Origin {
    /// The set's folder name ([`crate::sets::slug`]).
    pub set: &'static str,
    /// The commit whose code it ran.
    pub commit: &'static str,
    /// The day it ran.
    pub measured: &'static str,
}

/// The committed sets. Measuring a set again: give its new commit here and
/// drop its [`CHANGES`] that came before that commit.
pub const ORIGINS: &[Origin] = &[
    Origin {
        set: "nvidia-h100-80gb-hbm3-vulkan",
        commit: "d7678c5",
        measured: "2026-11-26",
    },
    // Lessons 03 and 10 only: the adaptive filters' first GPU run.
    Origin {
        set: "nvidia-h200-vulkan",
        commit: "8768674",
        measured: "2026-11-27",
    },
];

/// A change, after the commit a measurement ran, to what it measured.
pub struct Change {
    /// The measurement's commit ([`Origin::commit`]).
    pub since: &'static str,
    pub lesson: &'static str,
    /// The variant, by the name the measurement gives it; `None`: what
    /// every variant of the lesson is measured against (the reference).
    pub variant: Option<&'static str>,
    /// The variant's name today, when it was renamed.
    pub now: Option<&'static str>,
    /// The commits that changed it.
    pub commits: &'static [&'static str],
    pub what: &'static str,
}

/// What changed since each measurement's commit, read from
/// `git log d7678c5..HEAD -- lessons/ shaders/ common/src/reference/` (and
/// from `8768674`, the H200 set's) and
/// checked against the book's own records of those commits.
/// Lesson 09's change, since the H100's run, to every variant's shadow
/// passes.
const fn cascade_culling(variant: &'static str) -> Change {
    Change {
        since: "d7678c5",
        lesson: "lesson_09",
        variant: Some(variant),
        now: None,
        commits: &["63f08fc"],
        what: "each cascade draws only the casters that can shadow its receivers, inside scissor rectangles (it drew every caster into every cascade, over the whole map): fewer shadow fragments, the same image",
    }
}

pub const CHANGES: &[Change] = &[
    Change {
        since: "d7678c5",
        lesson: "lesson_03",
        variant: Some("wgpu_example_hw2x2"),
        now: None,
        commits: &["b76feab"],
        what: "the wgpu example's own 512² map (it ran on 1024²)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_03",
        variant: Some("bevy"),
        now: None,
        commits: &["b76feab"],
        what: "Bevy's own 2048² map (it ran on 1024²)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_04",
        variant: Some("learnopengl_1tap"),
        now: None,
        commits: &["b76feab"],
        what: "LearnOpenGL's near plane (1 m, clipped), depth stored as distance / 25, no range clamp (it ran with a 5 cm near plane, unclipped)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_04",
        variant: Some("learnopengl_pcf20"),
        now: None,
        commits: &["b76feab"],
        what: "LearnOpenGL's near plane (1 m, clipped), depth stored as distance / 25, no range clamp (it ran with a 5 cm near plane, unclipped)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_04",
        variant: Some("bevy_point"),
        now: None,
        commits: &["b76feab"],
        what: "Bevy's near plane (0.1 m, clipped), its flipped Gaussian basis and its interpolated normal (it ran with a 5 cm near plane, unclipped)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("filament_pcss"),
        now: None,
        commits: &["b4352d7"],
        what: "Filament's first 16 Poisson points and its depth-averaged penumbra ratio",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("filament_evsm"),
        now: None,
        commits: &["b4352d7"],
        what: "Filament's EVSM floor with its exponent",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("bevy_pcss"),
        now: Some("bevy_pcss_or_pcf"),
        commits: &["b4352d7"],
        what: "Bevy's reversed infinite spot depth and its own width units; on a sun, Bevy's Castaño PCF",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("godot_soft_low"),
        now: None,
        commits: &["b4352d7"],
        what: "Godot's spot formula",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("threejs_pcf_soft"),
        now: None,
        commits: &["9a542e5"],
        what: "three.js's own 512² map (it ran on 1024²)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: Some("threejs_vsm"),
        now: None,
        commits: &["b4352d7", "9a542e5"],
        what: "three.js's VSM, the blur of its map's own depth, on its 512² map (it ran on 1024²)",
    },
    Change {
        since: "d7678c5",
        lesson: "lesson_10",
        variant: None,
        now: None,
        commits: &["0a5b04a"],
        what: "the exact reference: an area light's rays now go wherever a conservative cone query finds a caster, so this set's errors are against the reference as it was (its times do not depend on it)",
    },    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("filament_pcss"),
        now: None,
        commits: &["122f8ed", "60a5198"],
        what: "Filament's own shadow pass (front faces, its polygon offset) and receiver offsets (1 mm towards the light, its normal bias × sin θ), not the lesson's map",
    },
    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("filament_evsm"),
        now: None,
        commits: &["122f8ed"],
        what: "Filament's VSM moments of a map drawn without offsets (front faces), not the lesson's biased map",
    },
    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("bevy_pcss_or_pcf"),
        now: None,
        commits: &["122f8ed"],
        what: "Bevy's 2048² spot map (DirectionalLightShadowMap; it ran on 1024²), its front faces and its receiver offsets",
    },
    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("godot_soft_low"),
        now: None,
        commits: &["122f8ed", "60a5198"],
        what: "Godot's normal bias on the receiver (on a spot 10 / shadow_size per metre of distance × (1 − cos θ), on a sun 2 texels × sin θ) and a sun's 2048² split (it ran on 1024²)",
    },
    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("threejs_pcf_soft"),
        now: None,
        commits: &["122f8ed"],
        what: "three.js's back faces in the map, no receiver plane (it ran on the lesson's biased map with a receiver plane)",
    },
    Change {
        since: "8768674",
        lesson: "lesson_10",
        variant: Some("threejs_vsm"),
        now: None,
        commits: &["122f8ed"],
        what: "three.js's front faces, no offsets, and r182's variance floor",
    },
    cascade_culling("single_2048"),
    cascade_culling("k1"),
    cascade_culling("k2"),
    cascade_culling("k3"),
    cascade_culling("k4"),
    cascade_culling("k4_uniform"),
    cascade_culling("k4_log"),
    cascade_culling("k4_aabb"),
    cascade_culling("k4_nosnap"),
    cascade_culling("k4_aabb_nosnap"),
    cascade_culling("k4_noextend"),
    cascade_culling("k4_blend"),
];

/// The origin of the set in folder `set`, when [`ORIGINS`] has it.
pub fn origin(set: &str) -> Option<&'static Origin> {
    ORIGINS.iter().find(|o| o.set == set)
}

/// Which GPU a set is, by its folder name ([`crate::sets::slug`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gpu {
    H100,
    H200,
}

/// The GPU of the set in folder `set`, when the notes know it
/// ([`crate::gpus`]).
pub fn gpu(set: &str) -> Option<Gpu> {
    if set.starts_with("nvidia-h100") {
        Some(Gpu::H100)
    } else if set.starts_with("nvidia-h200") {
        Some(Gpu::H200)
    } else {
        None
    }
}

/// The changes since `commit` to `lesson`'s `variant` (by the name the
/// measurement gives it).
pub fn changed(commit: &str, lesson: &str, variant: &str) -> Option<&'static Change> {
    CHANGES
        .iter()
        .find(|c| c.since == commit && c.lesson == lesson && c.variant == Some(variant))
}

/// The changes since `commit` to what every variant of `lesson` is
/// measured against.
fn lesson_wide_changes<'a>(
    commit: &'a str,
    lesson: &'a str,
) -> impl Iterator<Item = &'static Change> + 'a {
    CHANGES
        .iter()
        .filter(move |c| c.since == commit && c.lesson == lesson && c.variant.is_none())
}

/// The commits as the book names them: `` `a` `` or `` `a` and `b` ``.
fn commits(c: &Change) -> String {
    let named: Vec<String> = c.commits.iter().map(|h| format!("`{h}`")).collect();
    named.join(" and ")
}

/// The note under a table of a measurement made at `commit`: the variants
/// of `lesson` it left out (`left_out`, by the measurement's names) and
/// why; with `lesson_wide`, also what changed since for every variant (the
/// reference their errors are measured against). `whose` names the rows
/// when the table holds other lessons too (`lesson 10's`).
pub fn changes_note(
    commit: &str,
    lesson: &str,
    left_out: &[&str],
    lesson_wide: bool,
    whose: Option<&str>,
) -> String {
    let mut s = String::new();
    let named: Vec<(&str, &Change)> = left_out
        .iter()
        .filter_map(|n| Some((*n, changed(commit, lesson, n)?)))
        .collect();
    if !named.is_empty() {
        let of = whose.map_or(String::new(), |w| format!(" of {w} rows"));
        s += &format!(
            "\nLeft out{of}: the variants changed since `{commit}`, whose figures here are of code the lesson no longer runs:\n\n"
        );
        for (name, c) in named {
            let renamed = c.now.map_or(String::new(), |n| format!(", now `{n}`"));
            s += &format!("- `{name}`{renamed} ({}): {}\n", commits(c), c.what);
        }
    }
    if lesson_wide {
        for c in lesson_wide_changes(commit, lesson) {
            s += &format!(
                "\nChanged since `{commit}`, for every variant ({}): {}.\n",
                commits(c),
                c.what
            );
        }
    }
    s
}

/// Every committed other set: its folder name and the records it has.
pub fn load_sets(generated: &Path) -> Result<Vec<(String, Vec<Record>)>> {
    let dir = generated.join(SETS_DIR);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut names: Vec<String> = entries
        .flatten()
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    let mut sets = Vec::new();
    for name in names {
        let mut records = Vec::new();
        for r in RUNS {
            let path = dir
                .join(&name)
                .join(r.lesson)
                .join(format!("{}.json", r.name));
            if let Ok(text) = std::fs::read_to_string(&path) {
                let rec: Record = serde_json::from_str(&text)
                    .with_context(|| format!("{}: not a record", path.display()))?;
                records.push(rec);
            }
        }
        sets.push((name, records));
    }
    Ok(sets)
}
