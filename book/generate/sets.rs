//! Records made on other adapters: `workbook book --adapter NAME` (or
//! `--backend gl`) measures every run of the manifest there and writes the
//! records and tables under `book/src/generated/sets/<adapter>-<backend>/`,
//! leaving the book's own set (lavapipe, Vulkan) as it is. Each chapter
//! then shows the other sets' tables beside lavapipe's
//! (`generated/<lesson>/results_other_adapters.md`), and the closing
//! chapter their tables of lesson 05's volume routes
//! (`choosing/volumes_build_sets.md`, [`volumes_build_sets`]).
//!
//! A set is measured at one commit ([`crate::origins::ORIGINS`]), and the code moves on.
//! A variant changed since that commit ([`CHANGES`]) is left out of the
//! set's tables and named under them with the commit that changed it, so
//! that no figure of code the lesson no longer runs sits beside today's.
//! The generator fails when a set's variant no longer exists, or runs with
//! other settings than the book's own record of the same run says, and
//! [`CHANGES`] does not say why ([`check_set`]).

use common::measure::counters::{
    FILTER_TAPS, FRAGMENT_SHADER_INVOCATIONS, FULL_DISK_PIXELS, PROBED_PIXELS, SHADOW_FRAGMENTS,
    SHADOW_TEXELS_WRITTEN, STENCIL_UPDATES, VOLUME_FRAGMENTS,
};
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};

use crate::manifest::{self, HD, RUNS, VOLUME_BUILDS};
use crate::record::Record;

use crate::origins::{changed, changes_note, load_sets, origin, CHANGES, SETS_DIR};

/// Counters that count rasterised fragments: adapters differ by a few at
/// triangle edges, so these alone do not say that a variant changed.
const RASTERISED: &[&str] = &[
    SHADOW_FRAGMENTS.name,
    SHADOW_TEXELS_WRITTEN.name,
    FRAGMENT_SHADER_INVOCATIONS.name,
    STENCIL_UPDATES.name,
    VOLUME_FRAGMENTS.name,
    // Lesson 03's adaptive filter: which pixels' probes straddle an edge
    // of the map, and so how many taps the frame made, is the rasteriser's.
    PROBED_PIXELS.name,
    FULL_DISK_PIXELS.name,
    FILTER_TAPS.name,
];

/// Fails when the set `name` (measured at `commit`) holds a variant that
/// the book's own record of the same run (`main`) does not have, or one
/// whose settings (its counters, bar the rasterised ones) differ from that
/// record's, without a [`CHANGES`] entry; or when [`CHANGES`] names a
/// variant of the set's commit that the set does not hold.
pub fn check_set(
    name: &str,
    commit: Option<&str>,
    records: &[Record],
    main: &[Record],
) -> Result<()> {
    let mut errors = Vec::new();
    for r in records {
        let Some(ours) = main.iter().find(|m| m.id() == r.id()) else {
            continue;
        };
        for v in &r.variants {
            if commit.is_some_and(|c| changed(c, &r.lesson, &v.name).is_some()) {
                continue;
            }
            let Some(today) = ours.variants.iter().find(|w| w.name == v.name) else {
                errors.push(format!(
                    "{}: `{}` is no variant of the lesson today",
                    r.id(),
                    v.name
                ));
                continue;
            };
            let differs: Vec<String> = v
                .counters
                .iter()
                .filter(|(k, _)| !RASTERISED.contains(&k.as_str()))
                .filter(|(k, n)| today.counters.get(*k) != Some(n))
                .map(|(k, n)| format!("{k} {n} → {:?}", today.counters.get(k)))
                .collect();
            if !differs.is_empty() {
                errors.push(format!(
                    "{}: `{}` ran with other settings than today's ({})",
                    r.id(),
                    v.name,
                    differs.join(", ")
                ));
            }
        }
    }
    if let Some(commit) = commit {
        for c in CHANGES.iter().filter(|c| c.since == commit) {
            let held = records.iter().any(|r| {
                r.lesson == c.lesson
                    && c.variant
                        .is_none_or(|n| r.variants.iter().any(|v| v.name == n))
            });
            let lesson_held = records.iter().any(|r| r.lesson == c.lesson);
            if lesson_held && !held {
                errors.push(format!(
                    "CHANGES names {}'s `{}`, which the set does not hold",
                    c.lesson,
                    c.variant.unwrap_or("")
                ));
            }
        }
    }
    if !errors.is_empty() {
        bail!(
            "the set {name}{} differs from the book's records; name each change, with the commit that made it, in origins::CHANGES (or measure the set again):\n  {}",
            commit.map_or(String::new(), |c| format!(" (measured at {c})")),
            errors.join("\n  ")
        );
    }
    Ok(())
}

/// Whether `--adapter` and `--backend` make the book's own set.
pub fn is_main(adapter: &str, backend: &str) -> bool {
    adapter == manifest::ADAPTER && backend == manifest::BACKEND
}

/// A set's folder name: the adapter's name and the backend, in lower case,
/// runs of other characters made one `-`
/// (`NVIDIA H100 80GB HBM3`, `Vulkan` → `nvidia-h100-80gb-hbm3-vulkan`).
pub fn slug(adapter: &str, backend: &str) -> String {
    let mut s = String::new();
    for c in format!("{adapter} {backend}").chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').to_string()
}

/// The folder a set's records go to.
pub fn set_dir(generated: &Path, adapter: &str, backend: &str) -> PathBuf {
    generated.join(SETS_DIR).join(slug(adapter, backend))
}

/// A set's heading: its adapter and the commit it ran, and what its GPU
/// is ([`crate::gpus`]).
fn heading(name: &str, records: &[Record], sets: &[(String, Vec<Record>)]) -> String {
    let who = records
        .first()
        .map_or(name.to_string(), |r| r.adapter_label());
    let mut s = match origin(name) {
        Some(o) => format!(
            "**{who}, the code of commit `{}`** (measured {}; lavapipe's tables are of the code as it is now)\n\n",
            o.commit, o.measured
        ),
        None => format!("**{who}**\n\n"),
    };
    if let Some(note) = crate::gpus::set_note(name, sets) {
        s += &format!("What this GPU is: {note}.\n\n");
    }
    s
}

/// A run's table without the variants changed since the set's commit, and
/// the names of those left out.
fn table_of(r: &Record, commit: Option<&str>) -> Result<(String, Vec<String>)> {
    let mut shown = r.clone();
    let mut left_out = Vec::new();
    shown.variants.retain(|v| {
        let gone = commit.is_some_and(|c| changed(c, &r.lesson, &v.name).is_some());
        if gone {
            left_out.push(v.name.clone());
        }
        !gone
    });
    if shown.variants.is_empty() {
        return Ok((String::new(), left_out));
    }
    let mean_abs = manifest::MEAN_ABS_LESSONS.contains(&r.lesson.as_str());
    Ok((shown.table(mean_abs)?, left_out))
}

/// One set's part of a lesson's `results_other_adapters.md`: its default
/// run and its run at the window's size, less the variants changed since
/// its commit (returned, by name); or that it has no run of the lesson.
fn set_part(
    name: &str,
    records: &[Record],
    lesson: &str,
    sets: &[(String, Vec<Record>)],
) -> Result<(String, Vec<String>)> {
    let commit = origin(name).map(|o| o.commit);
    let mut s = heading(name, records, sets);
    let runs: Vec<&Record> = ["results", HD]
        .iter()
        .filter_map(|run| records.iter().find(|r| r.lesson == lesson && r.run == *run))
        .collect();
    let mut left_out: Vec<String> = Vec::new();
    if runs.is_empty() {
        let mut held: Vec<String> = records
            .iter()
            .map(|r| r.lesson.replace("lesson_", ""))
            .collect();
        held.sort();
        held.dedup();
        s += &format!(
            "*This set has no run of this lesson at the book's size, {}×{} (it holds lessons {} there).*\n",
            manifest::WIDTH,
            manifest::HEIGHT,
            held.join(", ")
        );
        return Ok((s, left_out));
    }
    for (i, r) in runs.iter().enumerate() {
        let (table, out) = table_of(r, commit)?;
        if i > 0 {
            s += &format!("\nThe same at {}×{}:\n\n", r.width, r.height);
        }
        s += &table;
        for n in out {
            if !left_out.contains(&n) {
                left_out.push(n);
            }
        }
    }
    Ok((s, left_out))
}

/// Each lesson's `results_other_adapters.md`: every other set's default
/// run and its run at the window's size (less the variants changed since
/// the set's commit, named under them), the same GPU's runs at 1920×1080
/// where they are committed ([`crate::gpu_costs`]), or how to make a set.
/// Fails when a set differs from the book's records in a way
/// [`CHANGES`] does not explain ([`check_set`]).
pub fn write_other_adapters(generated: &Path, sets: &[(String, Vec<Record>)]) -> Result<()> {
    let main = crate::record::load_records(generated)?;
    for (name, records) in sets {
        check_set(name, origin(name).map(|o| o.commit), records, &main)?;
    }
    let full_hd = crate::gpu_costs::load(generated)?;
    let mut lessons: Vec<&str> = RUNS.iter().map(|r| r.lesson).collect();
    lessons.dedup();
    for lesson in lessons {
        let mut parts = Vec::new();
        for (name, records) in sets {
            let commit = origin(name).map(|o| o.commit);
            let (mut part, mut left_out) = set_part(name, records, lesson, sets)?;
            // The reference's changes touch the errors: only where the set
            // shows this lesson's.
            let lesson_wide = records.iter().any(|r| r.lesson == lesson);
            if full_hd.set == name.as_str() {
                let (lines, out) = crate::gpu_costs::lesson_lines(&full_hd, lesson);
                if commit != Some(crate::gpu_costs::ORIGIN.commit) {
                    // Another commit than the set's: its own note.
                    let names: Vec<&str> = out.iter().map(String::as_str).collect();
                    part +=
                        &changes_note(crate::gpu_costs::ORIGIN.commit, lesson, &names, false, None);
                    part += &lines;
                } else {
                    part += &lines;
                    left_out.extend(
                        out.into_iter()
                            .filter(|n| !left_out.contains(n))
                            .collect::<Vec<_>>(),
                    );
                }
            }
            if let Some(c) = commit {
                let names: Vec<&str> = left_out.iter().map(String::as_str).collect();
                part += &changes_note(c, lesson, &names, lesson_wide, None);
            }
            parts.push(part);
        }
        let text = if parts.is_empty() {
            format!(
                "*Only lavapipe's records are committed. On a GPU, `cargo run --release --bin workbook -- book --adapter any` measures every run there and writes its set to `book/src/generated/{SETS_DIR}/<adapter>-<backend>/`; its table then appears here, beside lavapipe's.*\n"
            )
        } else {
            parts.join("\n")
        };
        let path = generated.join(lesson).join("results_other_adapters.md");
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

/// Every other set's table of the three ways to build the volumes
/// ([`crate::choosing::volumes_build`] on the set's records), less the
/// variants changed since the set's commit.
pub fn volumes_build_sets(generated: &Path) -> Result<String> {
    let mut s = String::new();
    for (name, records) in load_sets(generated)? {
        let commit = origin(&name).map(|o| o.commit);
        let mut left_out = Vec::new();
        let mine: Vec<Record> = records
            .iter()
            .filter(|r| VOLUME_BUILDS.iter().any(|(id, _)| *id == r.id()))
            .map(|r| {
                let mut r = r.clone();
                r.variants.retain(|v| {
                    let gone = commit.is_some_and(|c| changed(c, &r.lesson, &v.name).is_some());
                    if gone && !left_out.contains(&v.name) {
                        left_out.push(v.name.clone());
                    }
                    !gone
                });
                r
            })
            .collect();
        if mine.is_empty() {
            continue;
        }
        if !s.is_empty() {
            s += "\n";
        }
        s += &match origin(&name) {
            Some(o) => format!(
                "**The code of commit `{}`** (measured {})\n\n",
                o.commit, o.measured
            ),
            None => String::new(),
        };
        s += &crate::choosing::volumes_build(&mine);
        if let Some(c) = commit {
            let names: Vec<&str> = left_out.iter().map(String::as_str).collect();
            s += &changes_note(c, "lesson_05", &names, false, None);
        }
    }
    if s.is_empty() {
        s = "*No set of another adapter has lesson 05's runs.*\n".into();
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::measure::counters::SHADOW_MAP_SIZE;

    #[test]
    fn set_names_come_from_the_adapter_and_backend() {
        assert_eq!(
            slug("NVIDIA H100 80GB HBM3", "Vulkan"),
            "nvidia-h100-80gb-hbm3-vulkan"
        );
        assert_eq!(
            slug("llvmpipe (LLVM 15.0.6, 256 bits)", "Gl"),
            "llvmpipe-llvm-15-0-6-256-bits-gl"
        );
        assert!(is_main("software", "vulkan"));
        assert!(!is_main("software", "gl") && !is_main("any", "vulkan"));
    }

    #[test]
    fn every_change_is_of_a_known_measurement_and_names_its_commits() {
        for c in CHANGES {
            assert!(
                crate::origins::ORIGINS.iter().any(|o| o.commit == c.since)
                    || c.since == crate::gpu_costs::ORIGIN.commit,
                "{}: since {}",
                c.lesson,
                c.since
            );
            assert!(!c.commits.is_empty() && !c.what.is_empty(), "{}", c.lesson);
        }
    }

    fn record(lesson: &str, variants: &[(&str, u64)]) -> Record {
        let v = |name: &str, size: u64| crate::record::VariantRecord {
            name: name.into(),
            receiver_pixels: 1,
            misclassified_pct: 0.0,
            false_shadow_pct: 0.0,
            false_lit_pct: 0.0,
            mean_abs: 0.0,
            coverage_mismatch_pct: 0.0,
            counters: [
                (SHADOW_MAP_SIZE.name.to_string(), size),
                (SHADOW_FRAGMENTS.name.to_string(), size * 3),
            ]
            .into(),
            timing: None,
            camera_path: None,
            classes: Vec::new(),
            soft: None,
            fragile: None,
        };
        Record {
            lesson: lesson.into(),
            run: "results".into(),
            scene: "default".into(),
            title: "default scene".into(),
            adapter: "A".into(),
            backend: "Vulkan".into(),
            width: 640,
            height: 360,
            repeats: 1,
            frames: 0,
            timing_source: String::new(),
            warm_up_ms: None,
            variants: variants.iter().map(|(n, s)| v(n, *s)).collect(),
            baseline: None,
        }
    }

    #[test]
    fn a_set_that_differs_from_the_records_must_say_why() {
        let today = [record("lesson_03", &[("poisson_16", 1024), ("bevy", 2048)])];
        // The same settings (the rasterised counts aside): nothing to say.
        let mut same = record("lesson_03", &[("poisson_16", 1024), ("bevy", 2048)]);
        same.variants[0]
            .counters
            .insert(SHADOW_FRAGMENTS.name.into(), 7);
        assert!(check_set("x", None, &[same], &today).is_ok());
        // Another map size, unexplained: fails, naming the variant.
        let today = [record(
            "lesson_03",
            &[
                ("poisson_16", 1024),
                ("bevy", 2048),
                ("wgpu_example_hw2x2", 512),
            ],
        )];
        let old = [record(
            "lesson_03",
            &[
                ("poisson_16", 1024),
                ("bevy", 1024),
                ("wgpu_example_hw2x2", 1024),
            ],
        )];
        let e = check_set("x", None, &old, &today).unwrap_err().to_string();
        assert!(
            e.contains("`bevy`") && e.contains(SHADOW_MAP_SIZE.name),
            "{e}"
        );
        // Explained by CHANGES (bevy's map since d7678c5): passes, and the
        // table leaves it out.
        assert!(check_set("x", Some("d7678c5"), &old, &today).is_ok());
        let (_, out) = table_of(&old[0], Some("d7678c5")).unwrap();
        assert_eq!(
            out,
            vec!["bevy".to_string(), "wgpu_example_hw2x2".to_string()]
        );
        // A variant that no longer exists, unexplained: fails.
        let gone = [record(
            "lesson_03",
            &[("poisson_16", 1024), ("pcf_9x9", 1024)],
        )];
        assert!(check_set("x", None, &gone, &today).is_err());
        // A change named for a variant the set does not hold: fails.
        let without = [record("lesson_03", &[("poisson_16", 1024)])];
        let e = check_set("x", Some("d7678c5"), &without, &today)
            .unwrap_err()
            .to_string();
        assert!(e.contains("wgpu_example_hw2x2"), "{e}");
    }

    #[test]
    fn the_note_names_each_left_out_variant_with_its_commit() {
        let note = changes_note(
            "d7678c5",
            "lesson_10",
            &["bevy_pcss", "threejs_vsm"],
            true,
            None,
        );
        assert!(
            note.contains("`bevy_pcss`, now `bevy_pcss_or_pcf` (`b4352d7`)"),
            "{note}"
        );
        assert!(
            note.contains("`threejs_vsm` (`b4352d7` and `9a542e5`)"),
            "{note}"
        );
        assert!(note.contains("`0a5b04a`"), "{note}");
        assert_eq!(changes_note("d7678c5", "lesson_05", &[], true, None), "");
        // The GPU cost table's rows of several lessons: whose they are,
        // and no reference note (its times do not depend on it).
        let rows = changes_note(
            "d7678c5",
            "lesson_10",
            &["godot_soft_low"],
            false,
            Some("lesson 10's"),
        );
        assert!(
            rows.contains("Left out of lesson 10's rows") && !rows.contains("0a5b04a"),
            "{rows}"
        );
    }
}
