//! Reading a snapshot's lines: their words and numbers ([`pieces`]), the
//! marks of the figures that are not portable ([`unmark`]), the numbers
//! that carry a bound ([`bounded`]), and a line a run wrote without bounds
//! read with the committed line's ([`with_committed_bounds`]).

use super::table::{class_of, Class};
use crate::portable::{Side, NOT_PORTABLE};

/// `line` with each [`not_portable`](crate::portable::not_portable) mark written as a plain ` ±B`, and
/// the side each marked figure keeps, by the figure's place among the
/// line's numbers. A mark that does not parse stays (its words then differ).
pub(super) fn unmark(line: &str) -> (String, Vec<(usize, Side)>) {
    let (mut out, mut marks, mut rest) = (String::new(), Vec::new(), line);
    while let Some(i) = rest.find(NOT_PORTABLE) {
        let after = &rest[i + NOT_PORTABLE.len()..];
        let parsed = after.split_once(')').and_then(|(inner, tail)| {
            let (bound, side) = inner.split_once(", ")?;
            let (word, t) = side.strip_suffix('%')?.split_once(' ')?;
            let t: f64 = t.parse().ok()?;
            let side = match word {
                "above" => Side::Above(t),
                "below" => Side::Below(t),
                _ => return None,
            };
            Some((bound, side, tail))
        });
        let Some((bound, side, tail)) = parsed else {
            break;
        };
        out.push_str(&rest[..i]);
        let figure = pieces(&out)
            .iter()
            .filter(|p| matches!(p, Piece::Number { .. }))
            .count();
        marks.push((figure.saturating_sub(1), side));
        out.push_str(" ±");
        out.push_str(bound);
        rest = tail;
    }
    out.push_str(rest);
    (out, marks)
}

/// `new`, a line the run wrote without bounds (it measured none: another
/// adapter than the snapshot's, `support::measure_bounds`), with the
/// committed line's bounds: `committed` with each figure replaced by
/// `new`'s, each bound (`±B`) kept. `None` when `new` has bounds of its
/// own, `committed` has none, or their words differ once the bounds are
/// left out (the caller then compares `new` as it is, and reports it).
pub(super) fn with_committed_bounds(committed: &str, new: &str) -> Option<String> {
    if new.contains('±') || !committed.contains('±') {
        return None;
    }
    let figures: Vec<&str> = pieces(new)
        .into_iter()
        .filter_map(|p| match p {
            Piece::Number { text, .. } => Some(text),
            Piece::Words(_) => None,
        })
        .collect();
    let (mut with, mut without, mut words, mut k) = (String::new(), String::new(), "", 0);
    for p in pieces(committed) {
        match p {
            Piece::Words(w) => {
                with.push_str(w);
                without.push_str(w.trim_end().strip_suffix('±').unwrap_or(w));
                words = w;
            }
            Piece::Number { text, .. } if introduces_bound(words) => with.push_str(text),
            Piece::Number { .. } => {
                let figure = figures.get(k)?;
                with.push_str(figure);
                without.push_str(figure);
                k += 1;
            }
        }
    }
    let shape = |line: &str| -> Vec<String> {
        let words: Vec<String> = (pieces(line).into_iter())
            .map(|p| match p {
                Piece::Words(w) => squeeze(w),
                Piece::Number { .. } => "#".to_string(),
            })
            .collect();
        squeeze(&words.join(" "))
            .split(' ')
            .map(str::to_string)
            .collect()
    };
    (k == figures.len() && shape(&without) == shape(new)).then_some(with)
}

/// A piece of a line: words, or a number as printed.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Piece<'a> {
    Words(&'a str),
    Number { text: &'a str, value: f64 },
}

/// Splits a line into words and numbers. A number is digits with an
/// optional fraction that does not touch a letter, digit, `_` or `.`
/// (so `res_256`, `k4`, `7x7` and `1e5` stay words).
pub(super) fn pieces(line: &str) -> Vec<Piece<'_>> {
    let b = line.as_bytes();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'.';
    let mut out = Vec::new();
    let (mut i, mut start) = (0, 0);
    while i < b.len() {
        let starts_number = b[i].is_ascii_digit() && (i == 0 || !word(b[i - 1]));
        if starts_number {
            let mut j = i;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            if j + 1 < b.len() && b[j] == b'.' && b[j + 1].is_ascii_digit() {
                j += 1;
                while j < b.len() && b[j].is_ascii_digit() {
                    j += 1;
                }
            }
            let touches = j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'_');
            if !touches {
                if start < i {
                    out.push(Piece::Words(&line[start..i]));
                }
                let text = &line[i..j];
                out.push(Piece::Number {
                    text,
                    value: text.parse().unwrap_or(f64::NAN),
                });
                start = j;
                i = j;
                continue;
            }
            // Part of a word: skip to its end.
            while i < b.len() && word(b[i]) {
                i += 1;
            }
            continue;
        }
        i += line[i..].chars().next().map_or(1, char::len_utf8);
    }
    if start < line.len() {
        out.push(Piece::Words(&line[start..]));
    }
    out
}

/// Words with runs of spaces collapsed (padding follows numbers' widths).
pub(super) fn squeeze(words: &str) -> String {
    words.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// One unit of the last printed digit of `text`.
pub(super) fn unit(text: &str) -> f64 {
    match text.split_once('.') {
        Some((_, frac)) => 10f64.powi(-(frac.len() as i32)),
        None => 1.0,
    }
}

/// The rounding of a printed number: one unit of its last digit, none for
/// a whole number (a count).
pub(super) fn rounding(text: &str) -> f64 {
    if text.contains('.') {
        unit(text)
    } else {
        0.0
    }
}

/// A mask row: only mask characters (and at least one of them or a space).
pub(super) fn is_mask_row(line: &str) -> bool {
    line.len() >= 8 && line.chars().all(|c| matches!(c, '#' | '.' | ':' | ' '))
}

/// Whether `words` (the text between two numbers) introduces a bound:
/// it ends with `±`.
pub(super) fn introduces_bound(words: &str) -> bool {
    words.trim_end().ends_with('±')
}

/// A number printed with its bound on a snapshot's line.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounded {
    /// Its key ([`class_of`]) and class.
    pub key: &'static str,
    pub class: Class,
    pub value: f64,
    pub bound: f64,
    /// The side it is tested by, when the line marks it not portable.
    pub marked: Option<Side>,
}

/// Every number of `line` that has a bound (`±B`, or a mark that it is
/// not portable), in order.
pub fn bounded(line: &str) -> Vec<Bounded> {
    let (plain, marks) = unmark(line);
    let ps = pieces(&plain);
    let mut out = Vec::new();
    let (mut words, mut number) = ("", 0);
    for (i, p) in ps.iter().enumerate() {
        match p {
            Piece::Words(w) => words = w,
            Piece::Number { value, .. } => {
                number += 1;
                if introduces_bound(words) {
                    continue;
                }
                if let (Some(Piece::Words(w)), Some(Piece::Number { value: b, .. })) =
                    (ps.get(i + 1), ps.get(i + 2))
                {
                    if introduces_bound(w) {
                        let (class, key) = class_of(words);
                        let marked = marks.iter().find(|(n, _)| *n + 1 == number);
                        out.push(Bounded {
                            key,
                            class,
                            value: *value,
                            bound: *b,
                            marked: marked.map(|m| m.1),
                        });
                    }
                }
            }
        }
    }
    out
}
