//! Claims: the sentences built on the measured figures, checked on the same
//! records as the figures. A sentence that compares measured figures
//! carries, invisible in the rendered book, the comparison it makes:
//!
//! ```text
//! The cut halves the bleeding<!--claim: lesson_10/results:vsm:light_bleeding_pct
//!   > 1.5 * lesson_10/results:vsm_bleed_cut:light_bleeding_pct-->.
//! ```
//!
//! A claim is one or more comparisons joined by `;`, each `LEFT OP RIGHT`:
//!
//! - an operand is a product of factors joined by `*`, each a number or a
//!   record key as the figure markers name it (`RUN:VARIANT:FIELD`, see
//!   [`crate::prose`]); a key stands for its number (a percentage as the
//!   tables print it, a count, a time's median, a cost's difference of
//!   medians);
//! - `<`, `>`, `<=`, `>=`, `==` compare the numbers;
//! - between two times (a single key each side), `faster` and `slower` say
//!   the left one is measurably faster or slower than the right (their
//!   spreads do not overlap, the left median below or above), `nofaster`
//!   that it is not measurably faster (slower, or the spreads overlap),
//!   `apart` that their spreads do not overlap, `overlap` that they do: the
//!   book's "no measurable difference".
//!
//! `workbook book` and `workbook tables` fail, naming the chapter's line and
//! the claim, when a claim is false on the records they wrote;
//! `tests/book_claims.rs` fails the same way on the committed records, and
//! finds comparative sentences about measured figures that carry no claim.

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::prose::{self, Measured};

/// Opens a claim: `<!--claim: LEFT OP RIGHT-->`.
pub const OPEN: &str = "<!--claim:";

/// The comparisons a claim may make.
const OPS: &[&str] = &[
    "<=", ">=", "==", "<", ">", "faster", "slower", "nofaster", "apart", "overlap",
];

/// What a claim came to on the records.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    pub holds: bool,
    /// The comparison with its operands' values: `9.049 > 7.493`.
    pub shown: String,
}

/// Every claim in `markdown` outside code blocks, as `(line, claim)`.
pub fn claims(markdown: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fenced = false;
    let mut open: Option<(usize, String)> = None;
    for (n, line) in markdown.lines().enumerate() {
        let t = line.trim();
        if open.is_none() && (t.starts_with("```") || t.starts_with("~~~")) {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = line;
        if let Some((start, mut text)) = open.take() {
            match rest.find("-->") {
                Some(end) => {
                    text.push(' ');
                    text.push_str(&rest[..end]);
                    out.push((start, text.split_whitespace().collect::<Vec<_>>().join(" ")));
                    rest = &rest[end + 3..];
                }
                None => {
                    text.push(' ');
                    text.push_str(rest);
                    open = Some((start, text));
                    continue;
                }
            }
        }
        while let Some(at) = rest.find(OPEN) {
            let after = &rest[at + OPEN.len()..];
            match after.find("-->") {
                Some(end) => {
                    let text = after[..end].split_whitespace().collect::<Vec<_>>();
                    out.push((n + 1, text.join(" ")));
                    rest = &after[end + 3..];
                }
                None => {
                    open = Some((n + 1, after.to_string()));
                    break;
                }
            }
        }
    }
    if let Some((start, text)) = open {
        out.push((start, text));
    }
    out
}

/// One side of a comparison.
enum Operand {
    /// A single key: its measure, kept for the spread-aware comparisons.
    Key(Measured),
    /// A product of numbers and keys.
    Product(f64, String),
}

impl Operand {
    fn number(&self) -> f64 {
        match self {
            Operand::Key(m) => m.number(),
            Operand::Product(x, _) => *x,
        }
    }
}

fn operand(text: &str, lookup: &mut dyn FnMut(&str) -> Result<Measured>) -> Result<Operand> {
    let factors: Vec<&str> = text.split('*').map(str::trim).collect();
    if factors.iter().any(|f| f.is_empty()) {
        bail!("an empty factor in `{text}`");
    }
    if let [one] = factors.as_slice() {
        if one.contains(':') {
            return Ok(Operand::Key(lookup(one)?));
        }
    }
    let mut x = 1.0;
    let mut shown = Vec::new();
    for f in factors {
        if f.contains(':') {
            let v = lookup(f)?.number();
            shown.push(format!("{}", round(v)));
            x *= v;
        } else {
            let v: f64 = f.parse().with_context(|| {
                format!("`{f}` is neither a number nor a RUN:VARIANT:FIELD key")
            })?;
            shown.push(f.to_string());
            x *= v;
        }
    }
    Ok(Operand::Product(x, shown.join(" × ")))
}

fn shown(o: &Operand) -> String {
    match o {
        Operand::Key(Measured::Time(s)) => {
            format!("{:.3} [{:.3}, {:.3}]", s.median, s.q25, s.q75)
        }
        Operand::Key(m) => format!("{}", round(m.number())),
        Operand::Product(x, how) if how.contains('×') => format!("{how} = {}", round(*x)),
        Operand::Product(x, _) => format!("{}", round(*x)),
    }
}

fn round(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// Evaluates one comparison `LEFT OP RIGHT`.
fn comparison(text: &str, lookup: &mut dyn FnMut(&str) -> Result<Measured>) -> Result<Outcome> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let ops: Vec<usize> = (0..words.len())
        .filter(|&i| OPS.contains(&words[i]))
        .collect();
    let [at] = ops.as_slice() else {
        bail!("a comparison is `LEFT OP RIGHT` with one of {OPS:?}, not `{text}`");
    };
    let op = words[*at];
    let (left, right) = (words[..*at].join(" "), words[at + 1..].join(" "));
    if left.is_empty() || right.is_empty() {
        bail!("`{op}` needs an operand on each side in `{text}`");
    }
    let (l, r) = (operand(&left, lookup)?, operand(&right, lookup)?);
    let holds = match op {
        "<" => l.number() < r.number(),
        ">" => l.number() > r.number(),
        "<=" => l.number() <= r.number(),
        ">=" => l.number() >= r.number(),
        "==" => (l.number() - r.number()).abs() <= 1e-9 * l.number().abs().max(1.0),
        _ => {
            let (Operand::Key(Measured::Time(a)), Operand::Key(Measured::Time(b))) = (&l, &r)
            else {
                bail!("`{op}` compares two times, one key each side, in `{text}`");
            };
            match op {
                "faster" => a.q75 < b.q25,
                "slower" => a.q25 > b.q75,
                // Not measurably faster: slower, or within each other's spread.
                "nofaster" => a.q75 >= b.q25,
                "apart" => a.differs_from(b),
                _ => !a.differs_from(b),
            }
        }
    };
    Ok(Outcome {
        holds,
        shown: format!("{} {op} {}", shown(&l), shown(&r)),
    })
}

/// Evaluates a claim (comparisons joined by `;`): it holds when all do.
/// `shown` gives every comparison when it holds, else the false ones.
pub fn eval(claim: &str, lookup: &mut dyn FnMut(&str) -> Result<Measured>) -> Result<Outcome> {
    let mut parts = Vec::new();
    for part in claim.split(';').map(str::trim).filter(|p| !p.is_empty()) {
        parts.push(comparison(part, lookup)?);
    }
    if parts.is_empty() {
        bail!("an empty claim");
    }
    let holds = parts.iter().all(|o| o.holds);
    let shown: Vec<String> = parts
        .into_iter()
        .filter(|o| holds || !o.holds)
        .map(|o| o.shown)
        .collect();
    Ok(Outcome {
        holds,
        shown: shown.join("; "),
    })
}

/// A key's measure, read from the records under `generated`.
pub fn lookup(generated: &Path, key: &str) -> Result<Measured> {
    let (record, variant, field) = prose::read(generated, key)?;
    prose::measure(&record, variant, field)
}

/// One line for every claim under `root/book/src` that is false (or cannot
/// be read) on the records under `generated`: `book/src/FILE:LINE: ...`.
pub fn false_claims(root: &Path, generated: &Path) -> Result<Vec<String>> {
    false_claims_in(root, generated, &prose::chapters(&root.join("book/src"))?)
}

/// [`false_claims`] of the pages named only.
pub fn false_claims_in(
    root: &Path,
    generated: &Path,
    pages: &[std::path::PathBuf],
) -> Result<Vec<String>> {
    let mut errors = Vec::new();
    for ch in pages {
        let ch = ch.as_path();
        let text = std::fs::read_to_string(ch)?;
        let name = ch.strip_prefix(root).unwrap_or(ch).display().to_string();
        for (line, claim) in claims(&text) {
            match eval(&claim, &mut |k| lookup(generated, k)) {
                Ok(o) if o.holds => {}
                Ok(o) => errors.push(format!(
                    "{name}:{line}: the claim `{claim}` is false: {}",
                    o.shown
                )),
                Err(e) => errors.push(format!("{name}:{line}: the claim `{claim}`: {e:#}")),
            }
        }
    }
    Ok(errors)
}

/// Fails, one line per claim, when a chapter's claim is false on the records.
pub fn check_book(root: &Path, generated: &Path) -> Result<()> {
    let errors = false_claims(root, generated)?;
    if !errors.is_empty() {
        bail!(
            "a sentence says what the records do not:\n{}",
            errors.join("\n")
        );
    }
    Ok(())
}
