//! The sentences made from the costs: which variants meet the budget, by
//! variant and by family (`choosing/gpu_budget.md`), and each lesson's
//! lines for its chapter ([`lesson_lines`]).

use super::costs::{rows, signed, time, Cost, FullHd, Row, Verdict};
use super::{BUDGET_MS, ORIGIN};
use crate::manifest::FAMILIES;

/// `lesson 05 `zpass_cpu` (+0.22 ms)`.
fn named(x: &Row, c: Cost) -> String {
    format!(
        "lesson {} `{}` ({} ms)",
        x.lesson,
        x.variant.name,
        signed(c.median)
    )
}

/// `a`, `a and b`, `a, b and c`.
fn and_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// `lesson 02`, `lessons 05, 06 and 07`.
fn lessons(ns: &[String]) -> String {
    match ns.len() {
        1 => format!("lesson {}", ns[0]),
        _ => format!("lessons {}", and_list(ns)),
    }
}

/// List items, the last ending the sentence.
fn items(lines: &[String]) -> String {
    let mut s = String::new();
    for (i, l) in lines.iter().enumerate() {
        let end = if i + 1 == lines.len() { '.' } else { ';' };
        s += &format!("- {l}{end}\n");
    }
    s
}

/// One family's line: its lessons with a variant within the budget, and
/// the others with their least costly variant.
fn family_line(family: &str, members: &[&str], all: &[Row]) -> Option<String> {
    let mut yes: Vec<String> = Vec::new();
    let mut no: Vec<(String, String)> = Vec::new();
    for lesson in members {
        let n = lesson.trim_start_matches("lesson_");
        let mine: Vec<(&Row, Cost)> = all
            .iter()
            .filter(|x| x.lesson == n)
            .filter_map(|x| Some((x, x.gpu_cost?)))
            .collect();
        if mine.iter().any(|(_, c)| c.verdict() == Verdict::Within) {
            yes.push(n.to_string());
        } else if let Some((x, c)) = mine.iter().min_by(|a, b| a.1.median.total_cmp(&b.1.median)) {
            no.push((
                n.to_string(),
                format!("`{}` {} ms", x.variant.name, signed(c.median)),
            ));
        }
    }
    if yes.is_empty() && no.is_empty() {
        return None;
    }
    let ns: Vec<String> = members
        .iter()
        .map(|l| l.trim_start_matches("lesson_").to_string())
        .collect();
    let span = match ns.as_slice() {
        [one] => format!("lesson {one}"),
        [first, .., last] => format!("lessons {first}–{last}"),
        [] => String::new(),
    };
    let least = |no: &[(String, String)]| -> String {
        match no {
            [(_, v)] => format!("none (its least costly: {v})"),
            _ => {
                let ns: Vec<String> = no.iter().map(|(n, _)| n.clone()).collect();
                let vs: Vec<String> = no.iter().map(|(_, v)| v.clone()).collect();
                format!(
                    "none in lessons {} (their least costly: {})",
                    and_list(&ns),
                    and_list(&vs)
                )
            }
        }
    };
    let text = match (yes.is_empty(), no.is_empty()) {
        (false, true) if yes.len() > 1 => "every lesson".to_string(),
        (false, true) => lessons(&yes),
        (true, _) => least(&no),
        (false, false) => format!("{}; {}", lessons(&yes), least(&no)),
    };
    Some(format!("{family} ({span}): {text}"))
}

/// The sentences that say which variants meet [`BUDGET_MS`], by variant
/// and by family, and why a cost can be below zero or the frame's over
/// the budget where the GPU's is not.
pub fn budget(full: &FullHd) -> String {
    let Some(first) = full.reports.first() else {
        return String::new();
    };
    let all: Vec<Row> = full.reports.iter().flat_map(|r| rows(r).0).collect();
    let with = |v: Verdict| -> Vec<String> {
        all.iter()
            .filter_map(|x| Some((x, x.gpu_cost?)))
            .filter(|(_, c)| c.verdict() == v)
            .map(|(x, c)| named(x, c))
            .collect()
    };
    let mut s = format!(
        "On the {} at {}×{}, the shadows' GPU time over the no-shadow frame (the table above):\n\n",
        first.adapter.name, first.width, first.height
    );
    let mut lines = Vec::new();
    for (v, what) in [
        (Verdict::Within, format!("within {BUDGET_MS} ms")),
        (Verdict::Over, format!("over {BUDGET_MS} ms")),
        (
            Verdict::OnTheLine,
            format!("on the line ({BUDGET_MS} ms lies within the spread)"),
        ),
    ] {
        let names = with(v);
        if !names.is_empty() {
            lines.push(format!("**{what}**: {}", and_list(&names)));
        }
    }
    s += &items(&lines);
    s += &format!("\nBy family, the lessons with a variant within {BUDGET_MS} ms:\n\n");
    let lines: Vec<String> = FAMILIES
        .iter()
        .filter_map(|(family, members)| family_line(family, members, &all))
        .collect();
    s += &items(&lines);
    let gpu_within = || {
        all.iter()
            .filter(|x| x.gpu_cost.is_some_and(|c| c.verdict() == Verdict::Within))
            .filter_map(|x| Some((x, x.frame_cost?)))
    };
    let frame_over: Vec<String> = gpu_within()
        .filter(|(_, c)| c.verdict() == Verdict::Over)
        .map(|(x, c)| named(x, c))
        .collect();
    let frame_line: Vec<String> = gpu_within()
        .filter(|(_, c)| c.verdict() == Verdict::OnTheLine)
        .map(|(x, c)| named(x, c))
        .collect();
    if !frame_over.is_empty() || !frame_line.is_empty() {
        let mut lines = Vec::new();
        if !frame_over.is_empty() {
            lines.push(format!("over {BUDGET_MS} ms: {}", and_list(&frame_over)));
        }
        if !frame_line.is_empty() {
            lines.push(format!(
                "on the line ({BUDGET_MS} ms within the spread): {}",
                and_list(&frame_line)
            ));
        }
        s += &format!(
            "\nWhere the GPU's time is within {BUDGET_MS} ms, the frame's, which counts the CPU's work too, need not be (the frame's cost in brackets):\n\n{}",
            items(&lines)
        );
    }
    for x in &all {
        let Some(c) = x.gpu_cost.filter(|c| c.high < 0.0) else {
            continue;
        };
        let r = full
            .reports
            .iter()
            .find(|r| r.lesson.ends_with(&x.lesson))
            .and_then(|r| r.baseline.as_ref());
        let Some(b) = r else {
            continue;
        };
        let quicker: Vec<String> = x
            .variant
            .timing_ms
            .keys()
            .filter(|k| !["total", "frame"].contains(&k.as_str()) && !k.starts_with("cpu"))
            .filter_map(|k| {
                let v = time(&x.variant.timing_ms, &x.variant.timing_spread_ms, k)?;
                let base = time(&b.timing_ms, &b.timing_spread_ms, k)?;
                (v.q75 < base.q25).then(|| {
                    format!(
                        "`{k}` takes {:.2} ms against the no-shadow frame's {:.2} ms",
                        v.median, base.median
                    )
                })
            })
            .collect();
        s += &format!(
            "\nBelow the no-shadow frame: lesson {} `{}` ({} ms of GPU time), where {}.\n",
            x.lesson,
            x.variant.name,
            signed(c.median),
            if quicker.is_empty() {
                "no pass alone is measurably quicker".into()
            } else {
                quicker.join(", ")
            }
        );
    }
    s
}

/// A lesson's lines for its chapter, under its set's tables: each variant
/// at 1920×1080, its shadows' GPU and frame cost and whether it meets the
/// budget; and the variants left out (changed since [`ORIGIN`]).
pub fn lesson_lines(full: &FullHd, lesson: &str) -> (String, Vec<String>) {
    let Some(r) = full.reports.iter().find(|r| r.lesson == lesson) else {
        return (String::new(), Vec::new());
    };
    let (rows, left_out) = rows(r);
    let mut s = format!(
        "\nAt {}×{} on the same GPU, the code of commit `{}`: the lesson run alone through its protocol, {} frames a variant (with every lesson's, against the half millisecond a shadow technique should cost there, in [Choosing a technique](choosing.md#on-a-gpu)):\n\n",
        r.width, r.height, ORIGIN.commit, r.frames
    );
    for x in &rows {
        let gpu = x.gpu_cost.map_or("unstable".into(), |c| c.cell());
        let frame = x.frame_cost.map_or("unstable".into(), |c| c.cell());
        let verdict = match x.gpu_cost.map(|c| c.verdict()) {
            Some(Verdict::Within) => format!("within {BUDGET_MS} ms"),
            Some(Verdict::Over) => format!("over {BUDGET_MS} ms"),
            Some(Verdict::OnTheLine) => format!("{BUDGET_MS} ms within its spread"),
            None => "—".into(),
        };
        s += &format!(
            "- `{}`: shadows {gpu} of GPU time ({verdict}); {frame} of frame time, the CPU's work included\n",
            x.variant.name
        );
    }
    (s, left_out.into_iter().map(String::from).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn and_list_joins_with_commas_and_a_last_and() {
        assert_eq!(
            and_list(&["a".into(), "b".into(), "c".into()]),
            "a, b and c"
        );
    }
}
