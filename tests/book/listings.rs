//! What a lesson chapter's listings hold: the technique as the chapter
//! teaches it, and nothing of the harness around it.
//!
//! Every listing a lesson chapter includes (`{{#include ..}}` of a file,
//! an anchor or a line range) is read as mdbook prints it, and each of its
//! lines, code and comments alike, is searched for the names in
//! [`HARNESS`]: the exercise switch, the counters, the timing, the
//! readbacks, the buffer view and the ports' model switches. Those live in
//! the lesson's harness (its `impl Lesson`, its `peers` module), outside
//! the functions the chapter prints. One name found fails the test, with
//! the chapter, the listing, the line and why the name is the harness's.
//!
//! Exempt: the coursework section's own files (`exercises.rs`,
//! `exercises.toml`, `exercises.wgsl`: the starter code and the grading
//! spec a student reads, where `exercise_` names are the point), and the
//! generated tables (`book/src/generated/`, results, not code).
//!
//! What is allowed: `frame.pass("name", |enc, ts| ..)` and wgpu's own
//! `timestamp_writes` field are how every pass of the workbook is recorded
//! (chapter 01 says so once); a name that is only in the harness never
//! needs them.

use std::fs;
use std::path::Path;

use crate::helpers::{fail_with, markdown_files, repo_root, Disk, Files, Memory};
use crate::parse::{normalize, parse_directives};
use crate::share::{chapter_lesson, listing_lines};

/// How a harness name is matched against one identifier of a line (a run
/// of ASCII letters, digits and `_`), or against the line's text.
#[derive(Debug, Clone, Copy)]
enum Name {
    /// The identifier is exactly this.
    Word(&'static str),
    /// The identifier starts with this (`exercise_` finds
    /// `exercise_blocker_search`).
    Prefix(&'static str),
    /// The identifier is this followed by an upper-case letter, or is this
    /// alone (`Exercise` finds `ExerciseSkipCasters`, not `Exercises`).
    Camel(&'static str),
    /// The identifier ends with this (`Stats` finds `PlanStats`).
    Suffix(&'static str),
    /// The line contains this text (for names that are not identifiers).
    Text(&'static str),
}

/// One harness name and why it marks the harness, not the technique.
struct Harness {
    name: Name,
    why: &'static str,
}

const fn h(name: Name, why: &'static str) -> Harness {
    Harness { name, why }
}

/// The names a printed technique listing must not hold, with why.
const HARNESS: &[Harness] = &[
    // The exercise switch: which student function a variant calls.
    h(
        Name::Word("student"),
        "the exercise switch (which of the student's functions a variant calls)",
    ),
    h(
        Name::Text("exercise!"),
        "the exercise switch (the macro that calls the student's code)",
    ),
    h(
        Name::Prefix("exercise_"),
        "a call into the student's code: the technique calls its own",
    ),
    h(
        Name::Camel("Exercise"),
        "an exercise variant: the coursework, not the technique",
    ),
    // Counting for the report.
    h(
        Name::Word("tally"),
        "the deterministic counters (the report's, not the technique's)",
    ),
    h(
        Name::Camel("Tally"),
        "the deterministic counters (the report's, not the technique's)",
    ),
    h(
        Name::Word("count_costs"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("count_fragments"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("count_texels"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("count_again"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("counters"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("Counters"),
        "counting for the report (measurement)",
    ),
    h(
        Name::Word("counted_on_frame"),
        "on which frame the harness counts",
    ),
    h(
        Name::Word("Instruments"),
        "the lesson's harness (measurement), not its technique",
    ),
    h(
        Name::Word("stats"),
        "counting what was drawn, for the report (derive it in the harness)",
    ),
    h(
        Name::Suffix("Stats"),
        "counting what was drawn, for the report (derive it in the harness)",
    ),
    // Timing.
    h(
        Name::Word("untimed"),
        "submits outside the timed frame: measurement",
    ),
    h(Name::Word("timestamp"), "timing"),
    h(Name::Word("timestamps"), "timing"),
    h(Name::Camel("Timestamp"), "timing"),
    h(Name::Word("query_set"), "timing"),
    h(Name::Word("QuerySet"), "timing"),
    h(Name::Word("Instant"), "timing on the CPU"),
    // Readbacks.
    h(
        Name::Word("readback"),
        "reading results back for the report",
    ),
    h(
        Name::Word("readbacks"),
        "reading results back for the report",
    ),
    h(
        Name::Prefix("read_back"),
        "reading results back for the report",
    ),
    h(
        Name::Word("map_async"),
        "reading results back for the report",
    ),
    // The buffer view (the window's view of a depth or stencil buffer).
    h(
        Name::Word("buffer_view"),
        "the window's buffer view, not the technique",
    ),
    h(
        Name::Word("BufferView"),
        "the window's buffer view, not the technique",
    ),
    h(
        Name::Text("\"buffer\" view"),
        "the window's buffer view, not the technique",
    ),
    // The ports' model switches: what a renderer does differently lives in
    // the lesson's peers module, written as the renderer writes it.
    h(
        Name::Word("search_model"),
        "a port's model switch: the renderers' ways live in the peers module",
    ),
    h(
        Name::Word("penumbra_model"),
        "a port's model switch: the renderers' ways live in the peers module",
    ),
    h(
        Name::Word("renderer_size"),
        "a port's model switch: the renderers' ways live in the peers module",
    ),
    h(
        Name::Word("search_at_receiver"),
        "a port's model switch: the renderers' ways live in the peers module",
    ),
];

/// Whether identifier `word` is `name`.
fn word_matches(word: &str, name: Name) -> bool {
    match name {
        Name::Word(w) => word == w,
        Name::Prefix(p) => word.starts_with(p),
        Name::Camel(c) => word.strip_prefix(c).is_some_and(|rest| {
            rest.is_empty() || rest.starts_with(|ch: char| ch.is_ascii_uppercase())
        }),
        Name::Suffix(s) => word.ends_with(s),
        Name::Text(_) => false,
    }
}

/// The identifiers of a line: runs of ASCII letters, digits and `_`.
fn identifiers(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
}

/// The first harness name on `line`: what was found and why it is the
/// harness's.
fn harness_name(line: &str) -> Option<(String, &'static str)> {
    for harness in HARNESS {
        if let Name::Text(t) = harness.name {
            if line.contains(t) {
                return Some((t.to_string(), harness.why));
            }
            continue;
        }
        if let Some(w) = identifiers(line).find(|w| word_matches(w, harness.name)) {
            return Some((w.to_string(), harness.why));
        }
    }
    None
}

/// Whether a listing from `file` is the coursework section's own: the
/// exercises' starter code and grading spec, where exercise names are
/// the point.
fn is_coursework(file: &Path) -> bool {
    file.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| matches!(n, "exercises.rs" | "exercises.toml" | "exercises.wgsl"))
}

/// One printed listing of a chapter and the lines it prints.
struct Printed {
    /// `file` or `file:anchor`, from the repository root.
    name: String,
    lines: Vec<String>,
}

/// The technique listings of chapter `chapter` (path from the repository
/// root): every include but the coursework's and the generated tables.
/// A listing that does not resolve is left to the includes test.
fn technique_listings(files: &dyn Files, chapter: &Path, markdown: &str) -> Vec<Printed> {
    let dir = chapter.parent().unwrap_or(Path::new(""));
    let mut out = Vec::new();
    for d in parse_directives(markdown) {
        let file = normalize(&dir.join(&d.path));
        if file.starts_with(dir.join("generated")) || is_coursework(&file) {
            continue;
        }
        let Some(source) = files.read(&file) else {
            continue;
        };
        let Some(lines) = listing_lines(&source, &d.part) else {
            continue;
        };
        let name = match &d.part {
            crate::parse::Part::Anchor(a) => format!("{}:{a}", file.display()),
            _ => format!("{}:{}", file.display(), d.line),
        };
        out.push(Printed {
            name,
            lines: lines.into_iter().map(str::to_string).collect(),
        });
    }
    out
}

/// Every harness name in a chapter's technique listings, one message each.
fn harness_in_listings(files: &dyn Files, chapter: &Path, markdown: &str) -> Vec<String> {
    let mut found = Vec::new();
    for listing in technique_listings(files, chapter, markdown) {
        for (n, line) in listing.lines.iter().enumerate() {
            if let Some((name, why)) = harness_name(line) {
                found.push(format!(
                    "{}: listing {} (its line {}): `{name}` is {why}: {}",
                    chapter.display(),
                    listing.name,
                    n + 1,
                    line.trim()
                ));
            }
        }
    }
    found
}

// ---------------------------------------------------------------------------
// The real book
// ---------------------------------------------------------------------------

#[test]
fn lesson_listings_hold_no_harness() {
    let root = repo_root();
    let mut errors = Vec::new();
    let mut chapters = 0;
    let mut listings = 0;
    for chapter in markdown_files(&root.join("book/src")) {
        let relative = chapter
            .strip_prefix(&root)
            .unwrap_or(&chapter)
            .to_path_buf();
        if chapter_lesson(&relative).is_none() || relative.parent() != Some(Path::new("book/src")) {
            continue;
        }
        let markdown = fs::read_to_string(&chapter)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", chapter.display()));
        chapters += 1;
        let disk = Disk(root.clone());
        let printed = technique_listings(&disk, &relative, &markdown);
        let lines: usize = printed.iter().map(|p| p.lines.len()).sum();
        eprintln!(
            "{}: {} technique listings, {lines} lines",
            relative.display(),
            printed.len()
        );
        listings += printed.len();
        errors.extend(harness_in_listings(&disk, &relative, &markdown));
    }
    assert!(
        chapters >= 10 && listings >= 50,
        "found {chapters} lesson chapters and {listings} technique listings: the checker read nothing"
    );
    fail_with(
        &errors,
        "a chapter prints its lesson's harness: move it out of the printed function \
         (into the lesson's `impl Lesson` or its peers module) and print the technique alone",
    );
}

// ---------------------------------------------------------------------------
// The checker's own tests, on in-memory text
// ---------------------------------------------------------------------------

#[test]
fn every_harness_name_is_found_and_lookalikes_are_not() {
    // Each kind of name, in code and in comments.
    for line in [
        "fn pcss(s: vec3<f32>, student: u32) -> f32 {",
        "let b = workbook::exercise!(lesson_05::volume_can_matter);",
        "b = exercise_blocker_search(s, search);",
        "if variant == Variant::ExerciseSkipCasters {",
        "tally: &TallyShader,",
        "self.costs[v] = Some(volumes.count_costs(gpu));",
        "let n = frame.untimed(|gpu| 1);",
        "let mut stats = PlanStats::default();",
        "// the timestamp of the pass",
        "let t = Instant::now();",
        "buffer.slice(..).map_async(wgpu::MapMode::Read, |_| {});",
        "// What the \"buffer\" view reads: this frame's stencil.",
        "if soft.search_model == 1u {",
        "fn counters(&self) {}",
    ] {
        assert!(harness_name(line).is_some(), "not found in: {line}");
    }
    // What the technique may say.
    for line in [
        "frame.pass(\"base\", |enc, ts| scene.base_pass(enc, targets, ts.render()));",
        "timestamp_writes: ts.render(),",
        "// Exercises come at the chapter's end.",
        "let search = filter_radius(d_r, min(soft.nearest_caster, d_r));",
        "// count the volumes into the stencil, then light where it is 0",
        "let statistics = 1; let reexercise = 2;",
        "let encounters = 3;",
    ] {
        assert_eq!(harness_name(line), None, "wrongly found in: {line}");
    }
}

#[test]
fn checker_reports_the_harness_in_a_printed_anchor_only() {
    let shader = "fn helper() { let student = 1u; }\n\
                  // ANCHOR: pcss\n\
                  fn pcss() -> f32 {\n    return 1.0;\n}\n\
                  // ANCHOR_END: pcss\n\
                  // ANCHOR: pcss_student\n\
                  fn pcss_student(student: u32) -> f32 {\n    return 1.0;\n}\n\
                  // ANCHOR_END: pcss_student\n";
    let files = Memory(
        [
            ("shaders/lesson_10/soft.wgsl", shader),
            (
                "lessons/lesson_10/exercises.rs",
                "pub fn exercise_blocker_search() {}\n",
            ),
        ]
        .into_iter()
        .map(|(p, s)| (p.into(), s.to_string()))
        .collect(),
    );
    let chapter = Path::new("book/src/lesson_10.md");
    // The clean anchor and the coursework file: nothing (the harness name
    // outside the anchor is not printed).
    let clean = "```wgsl\n{{#include ../../shaders/lesson_10/soft.wgsl:pcss}}\n```\n\
                 ```rust\n{{#include ../../lessons/lesson_10/exercises.rs}}\n```\n";
    assert_eq!(
        harness_in_listings(&files, chapter, clean),
        Vec::<String>::new()
    );
    // The anchor with the switch, and the whole file: found, each with
    // the listing, its line and why.
    let dirty = "{{#include ../../shaders/lesson_10/soft.wgsl:pcss_student}}\n\
                 {{#include ../../shaders/lesson_10/soft.wgsl}}\n";
    let found = harness_in_listings(&files, chapter, dirty);
    assert_eq!(found.len(), 3, "{found:#?}");
    assert!(
        found[0].contains("shaders/lesson_10/soft.wgsl:pcss_student (its line 1)")
            && found[0].contains("`student` is the exercise switch"),
        "{}",
        found[0]
    );
}
