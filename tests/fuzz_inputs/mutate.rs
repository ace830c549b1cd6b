//! The inputs: real files mutated the way a slip of the hand or a hostile
//! file would change them, soups of real lines, and plain random text.
//!
//! A mutated input starts from one seed file (a scene of `scenes/`, an OBJ,
//! a chapter's `exercises.toml`) and applies one to four [`Edit`]s: a
//! number replaced with an extreme value, a line deleted, duplicated,
//! swapped or inserted, a field deleted, a key (TOML) or tag (OBJ)
//! renamed, a value given another type, the text cut at a byte, or stray
//! bytes inserted. Every choice is a proptest strategy, so a failure
//! shrinks to few edits.

use std::fmt;

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::{select, Index};

use vocabulary::{extra_lines, EXTREMES, OBJ_NAMES, OBJ_VALUES, TOML_NAMES, TOML_VALUES};

#[path = "vocabulary.rs"]
mod vocabulary;

/// The syntax of a parser's files: what a key, a value and a line are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Syntax {
    /// `key = value` lines and `[table]` headers.
    Toml,
    /// A tag (`v`, `f`, ...) and its arguments on each line.
    Obj,
}

/// The material of one parser's inputs.
pub struct Seeds {
    pub syntax: Syntax,
    /// `(name, content)` of each seed file, in a fixed order.
    pub files: Vec<(String, Vec<u8>)>,
    /// Every distinct line of the seeds, then [`extra_lines`]: what
    /// [`Edit::InsertLine`] and the line soups draw from.
    pub lines: Vec<Vec<u8>>,
}

impl Seeds {
    pub fn new(syntax: Syntax, files: Vec<(String, Vec<u8>)>) -> Seeds {
        let mut lines: Vec<Vec<u8>> = Vec::new();
        let extra = extra_lines(syntax).iter().map(|l| l.as_bytes());
        for line in files
            .iter()
            .flat_map(|(_, f)| f.split(|&b| b == b'\n'))
            .chain(extra)
        {
            if !line.is_empty() && !lines.iter().any(|l| l == line) {
                lines.push(line.to_vec());
            }
        }
        Seeds {
            syntax,
            files,
            lines,
        }
    }
}

/// One change to a seed file. `Index` picks among what exists (lines,
/// numbers, bytes) whatever the file's length.
#[derive(Clone, Debug)]
pub enum Edit {
    /// The k-th number in the text becomes this.
    Number(Index, &'static str),
    DeleteLine(Index),
    /// A `key = value` line (TOML) or an element (OBJ): a field missing.
    DeleteKey(Index),
    DuplicateLine(Index),
    SwapLines(Index, Index),
    /// The k-th `key =` line's key or `[table]`'s name, or OBJ line's tag.
    Rename(Index, &'static str),
    /// What follows the k-th key's `=`, or the k-th OBJ line's arguments.
    Retype(Index, &'static str),
    /// The text ends at this byte.
    Truncate(Index),
    InsertBytes(Index, Vec<u8>),
    /// Line `.1` of [`Seeds::lines`], inserted before line `.0`.
    InsertLine(Index, Index),
}

/// An input and how it was made (what a failure prints).
#[derive(Clone)]
pub struct Case {
    pub origin: String,
    pub edits: Vec<Edit>,
    pub bytes: Vec<u8>,
}

impl fmt::Debug for Case {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} with {:?}:\n{}",
            self.origin,
            self.edits,
            String::from_utf8_lossy(&self.bytes)
        )
    }
}

/// One [`Edit`], with the vocabulary of `syntax`.
fn edit(syntax: Syntax) -> impl Strategy<Value = Edit> {
    let (names, values) = match syntax {
        Syntax::Toml => (TOML_NAMES, TOML_VALUES),
        Syntax::Obj => (OBJ_NAMES, OBJ_VALUES),
    };
    prop_oneof![
        4 => (any::<Index>(), select(EXTREMES)).prop_map(|(i, v)| Edit::Number(i, v)),
        1 => any::<Index>().prop_map(Edit::DeleteLine),
        2 => any::<Index>().prop_map(Edit::DeleteKey),
        1 => any::<Index>().prop_map(Edit::DuplicateLine),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Edit::SwapLines(a, b)),
        2 => (any::<Index>(), select(names)).prop_map(|(i, n)| Edit::Rename(i, n)),
        2 => (any::<Index>(), select(values)).prop_map(|(i, v)| Edit::Retype(i, v)),
        1 => any::<Index>().prop_map(Edit::Truncate),
        1 => (any::<Index>(), vec(stray_byte(), 1..6)).prop_map(|(i, b)| Edit::InsertBytes(i, b)),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Edit::InsertLine(a, b)),
    ]
}

/// Any byte, half the time one that means something to a parser.
fn stray_byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        any::<u8>(),
        select(&b"[]{}=\".,#\\'/ \n\r\t-+0123456789eE\0"[..])
    ]
}

/// The inputs of one parser: mutated seeds (7 in 10), soups of up to 24
/// of its lines (2 in 10), random text or bytes (1 in 10).
pub fn cases(seeds: std::sync::Arc<Seeds>) -> impl Strategy<Value = Case> {
    let (s1, s2) = (seeds.clone(), seeds.clone());
    let mutated = (any::<Index>(), vec(edit(seeds.syntax), 1..=4)).prop_map(move |(i, edits)| {
        let (name, text) = &s1.files[i.index(s1.files.len())];
        let mut bytes = text.clone();
        for e in &edits {
            apply(e, &mut bytes, &s1);
        }
        Case {
            origin: name.clone(),
            edits,
            bytes,
        }
    });
    let soup = vec(any::<Index>(), 0..24).prop_map(move |picks| {
        let lines: Vec<&[u8]> = picks
            .iter()
            .map(|i| &s2.lines[i.index(s2.lines.len())][..])
            .collect();
        Case {
            origin: "a soup of lines".into(),
            edits: Vec::new(),
            bytes: lines.join(&b'\n'),
        }
    });
    let random = prop_oneof![
        vec(stray_byte(), 0..160),
        vec(any::<char>(), 0..80).prop_map(|c| c.into_iter().collect::<String>().into_bytes()),
    ]
    .prop_map(|bytes| Case {
        origin: "random text".into(),
        edits: Vec::new(),
        bytes,
    });
    prop_oneof![7 => mutated, 2 => soup, 1 => random]
}

/// Applies one edit to `bytes`.
pub fn apply(edit: &Edit, bytes: &mut Vec<u8>, seeds: &Seeds) {
    let mut lines: Vec<Vec<u8>> = bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let n = lines.len();
    match edit {
        Edit::Number(i, value) => {
            let numbers = number_spans(bytes);
            if !numbers.is_empty() {
                let (a, b) = numbers[i.index(numbers.len())];
                bytes.splice(a..b, value.bytes());
            }
            return;
        }
        Edit::Truncate(i) => return bytes.truncate(i.index(bytes.len() + 1)),
        Edit::InsertBytes(i, stray) => {
            let at = i.index(bytes.len() + 1);
            bytes.splice(at..at, stray.iter().copied());
            return;
        }
        Edit::DeleteLine(i) => {
            lines.remove(i.index(n));
        }
        Edit::DeleteKey(i) => {
            if let Some(k) = pick(&lines, i, |l| is_keyed(l, seeds.syntax)) {
                lines.remove(k);
            }
        }
        Edit::DuplicateLine(i) => {
            let k = i.index(n);
            lines.insert(k, lines[k].clone());
        }
        Edit::SwapLines(a, b) => lines.swap(a.index(n), b.index(n)),
        Edit::InsertLine(at, which) => {
            let line = seeds.lines[which.index(seeds.lines.len())].clone();
            lines.insert(at.index(n + 1), line);
        }
        Edit::Rename(i, name) => {
            let header = |l: &[u8]| l.trim_ascii_start().starts_with(b"[");
            let named = |l: &[u8]| is_keyed(l, seeds.syntax) || header(l);
            if let Some(k) = pick(&lines, i, named) {
                lines[k] = rename(&lines[k], name, seeds.syntax);
            }
        }
        Edit::Retype(i, value) => {
            if let Some(k) = pick(&lines, i, |l| is_keyed(l, seeds.syntax)) {
                lines[k] = retype(&lines[k], value, seeds.syntax);
            }
        }
    }
    *bytes = lines.join(&b'\n');
}

/// The byte ranges of the numbers in `text`: a digit (or a sign or point
/// before one) not inside a word, and what follows of digits, `.`, `_`,
/// exponents and signs.
fn number_spans(text: &[u8]) -> Vec<(usize, usize)> {
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_' || b == b'.';
    let mut spans = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let next_digit = text.get(i + 1).is_some_and(u8::is_ascii_digit);
        let starts = text[i].is_ascii_digit() || (b"+-.".contains(&text[i]) && next_digit);
        if starts && (i == 0 || !word(text[i - 1])) {
            let mut j = i + 1;
            while j < text.len() && (text[j].is_ascii_digit() || b"._eE+-".contains(&text[j])) {
                j += 1;
            }
            spans.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    spans
}

/// The `i`-th of the lines for which `which` holds, if any does.
fn pick(lines: &[Vec<u8>], i: &Index, which: impl Fn(&[u8]) -> bool) -> Option<usize> {
    let found: Vec<usize> = (0..lines.len()).filter(|&k| which(&lines[k])).collect();
    (!found.is_empty()).then(|| found[i.index(found.len())])
}

/// A line that gives a value: `key = value` (TOML), or any element (OBJ).
fn is_keyed(line: &[u8], syntax: Syntax) -> bool {
    let text = String::from_utf8_lossy(line);
    let t = text.trim_start();
    let element = !t.is_empty() && !t.starts_with('#');
    match syntax {
        Syntax::Toml => element && !t.starts_with('[') && t.contains('='),
        Syntax::Obj => element,
    }
}

/// `line` with its key, table name or tag replaced by `name`; a line
/// with none of those is left as it is.
fn rename(line: &[u8], name: &str, syntax: Syntax) -> Vec<u8> {
    let text = String::from_utf8_lossy(line);
    let trimmed = text.trim_start();
    let out = match syntax {
        Syntax::Toml if trimmed.starts_with('[') => {
            let depth = trimmed.bytes().take_while(|&b| b == b'[').count();
            format!("{0}{name}{1}", "[".repeat(depth), "]".repeat(depth))
        }
        Syntax::Toml => match text.split_once('=') {
            Some((_, value)) => format!("{name} ={value}"),
            None => return line.to_vec(),
        },
        Syntax::Obj => match trimmed.split_once(char::is_whitespace) {
            Some((_, args)) => format!("{name} {args}"),
            None => name.to_string(),
        },
    };
    out.into_bytes()
}

/// `line` with its value (TOML) or its arguments (OBJ) replaced by `value`.
fn retype(line: &[u8], value: &str, syntax: Syntax) -> Vec<u8> {
    let text = String::from_utf8_lossy(line);
    let out = match syntax {
        Syntax::Toml => match text.split_once('=') {
            Some((key, _)) => format!("{key}= {value}"),
            None => return line.to_vec(),
        },
        Syntax::Obj => {
            let tag = text.split_whitespace().next().unwrap_or("v");
            format!("{tag} {value}")
        }
    };
    out.into_bytes()
}
