//! The README's results table and the plots' points, from the records of
//! the lessons' default runs: what each lesson's Pareto front is.

use crate::plots::{pareto_front, Metric, Point, Series};
use crate::record::Record;
use crate::table::{header, pct, row, stat};

/// The README's table sits between these two lines.
pub const BEGIN: &str =
    "<!-- results:begin (written by `cargo run --release --bin workbook -- book`; do not edit) -->";
pub const END: &str = "<!-- results:end -->";

/// One lesson's default run as plot points: the variants with stable
/// times, at their frame cost (`frame`: what a user waits per frame,
/// CPU work included), and their error: misclassified %, or for a soft
/// shadow the penumbra's mean |ΔV| % ([`crate::record::VariantRecord::error_pct`]).
pub fn series(r: &Record) -> Series {
    Series {
        name: r.lesson.clone(),
        metric: match r.soft() {
            true => Metric::PenumbraMeanAbs,
            false => Metric::Misclassified,
        },
        points: r
            .variants
            .iter()
            .filter_map(|v| {
                let t = v.timing.as_ref().filter(|t| t.stable())?;
                let f = t.frame();
                Some(Point {
                    label: v.name.clone(),
                    ms: f.median,
                    ms_low: f.q25,
                    ms_high: f.q75,
                    error_pct: v.error_pct(),
                })
            })
            .collect(),
    }
}

/// The README block: one row a lesson, its Pareto-optimal variants (no
/// other variant is both faster and more accurate, by median) with their
/// error and time, and the no-shadow baseline.
pub fn readme_block(defaults: &[&Record]) -> String {
    let Some(first) = defaults.first() else {
        return format!("{BEGIN}\n{END}\n");
    };
    let mut s = format!(
        "{BEGIN}\n{}\n\n",
        first
            .header()
            .replace(
                &format!("the default scene (`scenes/{}.toml`)", first.lesson),
                "each lesson's default scene",
            )
            // The README sits at the repository's root, not in the book.
            .replace(
                &format!("]({})", crate::table::PROTOCOL),
                &format!("](book/src/{})", crate::table::PROTOCOL),
            )
    );
    // A soft shadow's error is its penumbra's mean |ΔV|: the header says
    // so when a lesson has one, and so does each of its cells.
    let soft = defaults.iter().any(|r| r.soft());
    s += &header(&[
        "lesson".into(),
        match soft {
            false => "Pareto-optimal variants: misclassified %, frame cost ms [spread]".into(),
            true => "Pareto-optimal variants: misclassified % (soft shadows: mean \\|ΔV\\| % over the penumbra), frame cost ms [spread]".into(),
        },
        "no shadows, frame ms".into(),
        "chapter".into(),
    ]);
    for r in defaults {
        let ser = series(r);
        let front: Vec<String> = pareto_front(&ser.points)
            .into_iter()
            .map(|i| {
                let p = &ser.points[i];
                let v = &r
                    .variants
                    .iter()
                    .find(|v| v.name == p.label)
                    .expect("point of a variant");
                let what = match ser.metric {
                    Metric::Misclassified => "",
                    Metric::PenumbraMeanAbs => "penumbra \\|ΔV\\| ",
                };
                format!(
                    "`{}`: {what}{} %, {}",
                    p.label,
                    pct(p.error_pct),
                    stat(v.timing.as_ref().expect("timed").frame())
                )
            })
            .collect();
        let n = r.lesson.trim_start_matches("lesson_");
        s += &row(&[
            n.to_string(),
            front.join("; "),
            r.baseline
                .as_ref()
                .map_or("—".into(), |b| match b.stable() {
                    true => stat(b.frame()),
                    false => "unstable".into(),
                }),
            format!("[{n}](book/src/{}.md)", r.lesson),
        ]);
    }
    s += END;
    s += "\n";
    s
}

/// `text` with the block between the markers replaced by `block`.
pub fn splice(text: &str, block: &str) -> Option<String> {
    let a = text.find(BEGIN)?;
    let b = text[a..].find(END)? + a + END.len();
    let b = if text[b..].starts_with('\n') {
        b + 1
    } else {
        b
    };
    Some(format!("{}{block}{}", &text[..a], &text[b..]))
}
