//! The mutation scripts still mutate something.
//!
//! `.ci/snapshot-mutations` and `.ci/protocol-mutations` are not part of
//! `.ci/run` (they rebuild once per mutation), so nothing else notices when
//! the code they break moves: a mutation whose text is no longer in its
//! file is reported "not applied" only when someone runs the script, and a
//! test filter that names no test passes with zero tests. Lesson 04's face
//! table moved from `cube_map.rs` to `faces.rs` and its mutation went
//! unapplied that way until the script was run (2026-12-02).
//!
//! Each mutation's text must occur exactly once in its file (as the scripts
//! require), and each test it runs must exist.

use std::path::Path;

/// One entry of a script's `mutations=( ... )` array.
struct Mutation {
    script: &'static str,
    line: usize,
    file: String,
    from: String,
    /// The test names the entry runs, as cargo test filters.
    tests: Vec<String>,
}

/// The quoted entries of `mutations=( ... )`, split on `|`.
fn entries(script: &'static str) -> Vec<(usize, Vec<String>)> {
    let text = std::fs::read_to_string(script).unwrap_or_else(|e| panic!("{script}: {e}"));
    let mut inside = false;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t == "mutations=(" {
            inside = true;
        } else if inside && t == ")" {
            break;
        } else if inside && t.starts_with('"') && t.ends_with('"') && t.len() > 1 {
            let body = &t[1..t.len() - 1];
            out.push((i + 1, body.split('|').map(str::to_string).collect()));
        }
    }
    assert!(
        !out.is_empty(),
        "{script}: no mutations=( ... ) entries found"
    );
    out
}

fn snapshot_mutations() -> Vec<Mutation> {
    let script = ".ci/snapshot-mutations";
    entries(script)
        .into_iter()
        .map(|(line, f)| {
            assert!(
                f.len() == 5 || f.len() == 6,
                "{script}:{line}: lesson|file|from|to|what[|test]"
            );
            // The snapshot, or the test the entry names instead.
            let test = match f.get(5) {
                Some(t) => t.clone(),
                None => format!("lesson_{}_snapshot", f[0]),
            };
            Mutation {
                script,
                line,
                file: f[1].clone(),
                from: f[2].clone(),
                tests: vec![test],
            }
        })
        .collect()
}

fn protocol_mutations() -> Vec<Mutation> {
    let script = ".ci/protocol-mutations";
    entries(script)
        .into_iter()
        .map(|(line, f)| {
            assert_eq!(f.len(), 5, "{script}:{line}: file|from|to|args|what");
            // The args end with the test filter: `-p common NAME` or
            // `--features ... --test BIN NAME`.
            let filter = f[3].split_whitespace().last().unwrap_or("").to_string();
            Mutation {
                script,
                line,
                file: f[0].clone(),
                // The script reads `\n` as a line break (its python step).
                from: f[1].replace("\\n", "\n"),
                tests: vec![filter],
            }
        })
        .collect()
}

/// Every `.rs` file under the workspace's source folders, read.
fn sources() -> Vec<String> {
    fn walk(dir: &Path, out: &mut Vec<String>) {
        let Ok(read) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in read.flatten() {
            let p = entry.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(std::fs::read_to_string(&p).unwrap_or_default());
            }
        }
    }
    let mut out = Vec::new();
    for dir in ["common", "lessons", "tests", "grade", "book/generate"] {
        walk(Path::new(dir), &mut out);
    }
    out
}

fn problems(mutations: &[Mutation], sources: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for m in mutations {
        let at = format!("{}:{}", m.script, m.line);
        match std::fs::read_to_string(&m.file) {
            Err(e) => out.push(format!("{at}: {}: {e}", m.file)),
            Ok(text) => {
                let n = text.matches(&m.from).count();
                if n != 1 {
                    out.push(format!(
                        "{at}: the text to mutate occurs {n} times in {}, not once: {:?}",
                        m.file, m.from
                    ));
                }
            }
        }
        for t in &m.tests {
            // A filter matches any test whose name contains it.
            let named = sources
                .iter()
                .any(|s| s.contains(&format!("fn {t}")) || s.contains(&format!("({t},")));
            if !named {
                out.push(format!("{at}: the test filter `{t}` names no test"));
            }
        }
    }
    out
}

#[test]
fn every_mutation_applies_and_runs_a_test() {
    let sources = sources();
    let mut all = snapshot_mutations();
    all.extend(protocol_mutations());
    let found = problems(&all, &sources);
    assert!(
        found.is_empty(),
        "a mutation script would not break what it says (fix the entry):\n{}",
        found.join("\n")
    );
}

#[test]
fn a_moved_text_and_a_missing_test_are_reported() {
    let sources = sources();
    let stale = [
        Mutation {
            script: "test",
            line: 1,
            file: "lessons/lesson_04/cube_map.rs".into(),
            from: "(DVec3::NEG_Y, DVec3::NEG_Z),".into(),
            tests: vec!["lesson_04_snapshot".into()],
        },
        Mutation {
            script: "test",
            line: 2,
            file: "lessons/lesson_04/faces.rs".into(),
            from: "(DVec3::NEG_Y, DVec3::NEG_Z),".into(),
            tests: vec!["no_such_test_anywhere_xyz".into()],
        },
    ];
    let found = problems(&stale, &sources);
    assert_eq!(found.len(), 2, "{found:#?}");
    assert!(found[0].contains("occurs 0 times"), "{}", found[0]);
    assert!(found[1].contains("names no test"), "{}", found[1]);
}
