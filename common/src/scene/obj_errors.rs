//! OBJ errors in one line that names the file and, where it can, the line:
//! tobj's errors carry no line, and it checks face indices only when an
//! object ends, so the line is found here, in the text.

use std::io::{BufRead, Read};

use anyhow::anyhow;

/// Reads lines for tobj and remembers how far it got, for error messages.
pub(super) struct LineCounter<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) pos: usize,
}

impl LineCounter<'_> {
    /// The 1-based line tobj read last.
    pub(super) fn line(&self) -> usize {
        line_of(self.bytes, self.pos.saturating_sub(1))
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = (&self.bytes[self.pos..]).read(buf)?;
        self.pos += n;
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(&self.bytes[self.pos..])
    }
    fn consume(&mut self, amount: usize) {
        self.pos += amount;
    }
}

/// 1-based line of a byte offset.
pub(super) fn line_of(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The first line (1-based) for which `bad` says why it is wrong.
pub(super) fn find_line(text: &str, mut bad: impl FnMut(&str) -> bool) -> Option<(usize, &str)> {
    text.lines()
        .enumerate()
        .find(|(_, l)| bad(l))
        .map(|(i, l)| (i + 1, l.trim()))
}

pub(super) fn is_non_finite_vertex(line: &str) -> bool {
    vertex_has(line, |x| !x.is_finite())
}

/// A `v` line with a coordinate for which `bad` holds, as tobj reads it:
/// divided by `w` in `v x y z w`.
pub(super) fn vertex_has(line: &str, bad: impl Fn(f32) -> bool) -> bool {
    let words: Vec<&str> = line.split_whitespace().collect();
    let (xyz, w) = match words[..] {
        ["v", x, y, z, w] => ([x, y, z], w.parse::<f32>().unwrap_or(1.0)),
        ["v", x, y, z, ..] => ([x, y, z], 1.0),
        _ => return false,
    };
    xyz.iter()
        .any(|x| x.parse::<f32>().is_ok_and(|x| bad(x / w)))
}

/// One line naming the file, and the line where the problem is.
pub(super) fn tobj_error(e: tobj::LoadError, text: &str, file: &str, line: usize) -> anyhow::Error {
    use tobj::LoadError as E;
    let what = match e {
        E::PositionParseError => "cannot parse a vertex (expected `v x y z`)".to_string(),
        E::ScalingByZeroError => "vertex has w = 0".to_string(),
        E::ColorParseError => "vertex has a wrong number of values (expected `v x y z`, `v x y z w` or `v x y z r g b`)".to_string(),
        E::NormalParseError => "cannot parse a normal (expected `vn x y z`)".to_string(),
        E::TexcoordParseError => "cannot parse a texture coordinate (expected `vt u v`)".to_string(),
        E::FaceParseError => "cannot parse a face (expected `f` and indices like `1`, `1/2`, `1//3` or `1/2/3`)".to_string(),
        // tobj checks face indices only when an object ends: find the face ourselves.
        E::FaceVertexOutOfBounds
        | E::FaceTexCoordOutOfBounds
        | E::FaceNormalOutOfBounds
        | E::FaceColorOutOfBounds
        | E::InvalidPolygon => {
            return match find_bad_face(text).or_else(|| find_uncoloured_vertex(text)) {
                Some((line, why)) => anyhow!("{file}:{line}: {why}"),
                None => anyhow!("{file}: {e}"),
            };
        }
        other => other.to_string(),
    };
    anyhow!("{file}:{line}: {what}")
}

/// tobj reads `v x y z r g b` colours (up to the first that is not a
/// number) into a list of their own, which falls short of the vertices
/// when some `v` lines have none: the first such line, if another has one.
fn find_uncoloured_vertex(text: &str) -> Option<(usize, String)> {
    let (mut coloured, mut short) = (None, None);
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() == Some("v") {
            let rgb: Vec<&str> = words.skip(3).collect();
            let read = match rgb.len() {
                3 => rgb.iter().take_while(|w| w.parse::<f32>().is_ok()).count(),
                _ => 0,
            };
            coloured = coloured.or((read > 0).then_some(number + 1));
            short = short.or((read < 3).then_some(number + 1));
        }
    }
    let first = coloured?;
    Some((short?, format!("vertex without a colour of three numbers (r g b), but line {first} has colour values: give every vertex a colour or none")))
}

/// The first face with an index out of range, and what is wrong with it.
/// Indices count from 1; negative ones count back from the last element read.
fn find_bad_face(text: &str) -> Option<(usize, String)> {
    let tags = ["v", "vt", "vn"];
    // tobj checks a face when its object ends (at an `o` or `g` line, or
    // the file's end), against what was read by then: `ends`, per line.
    let (mut total, mut ends, mut start) = ([0usize; 3], Vec::new(), 0);
    for (i, line) in text.lines().enumerate() {
        let tag = line.split_whitespace().next();
        ends.push(total);
        if matches!(tag, Some("o" | "g")) {
            ends[start..i].fill(total);
            start = i;
        }
        if let Some(k) = tags.iter().position(|t| tag == Some(t)) {
            total[k] += 1;
        }
    }
    ends[start..].fill(total);
    let mut seen = [0usize; 3];
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let tag = words.next();
        if let Some(k) = tags.iter().position(|t| tag == Some(t)) {
            seen[k] += 1;
            continue;
        }
        // tobj reads `l` (a polyline) as it reads `f`.
        if !matches!(tag, Some("f" | "l")) {
            continue;
        }
        let words: Vec<&str> = words.collect();
        if words.is_empty() {
            return Some((
                number + 1,
                "face without indices (expected `f 1 2 3`)".into(),
            ));
        }
        let end = ends[number];
        for word in words {
            if word.starts_with('/') {
                return Some((
                    number + 1,
                    format!("face corner {word:?} has no vertex index"),
                ));
            }
            for (k, part) in word.split('/').enumerate().take(3) {
                let Ok(x) = part.parse::<i64>() else { continue };
                // tobj ignores vt and vn indices when the file has none.
                if k > 0 && end[k] == 0 {
                    continue;
                }
                let what = ["vertex", "texture coordinate", "normal"][k];
                let later = if end[k] < total[k] {
                    " by the end of its object (`o`, `g`)"
                } else {
                    ""
                };
                let why = if x == 0 {
                    Some(format!("face index 0 in {word:?} (OBJ indices start at 1)"))
                } else if x > 0 && x as usize > end[k] {
                    Some(format!(
                        "face refers to {what} {x} but the file has {}{later} ({word:?})",
                        end[k]
                    ))
                } else if x < 0 && x.unsigned_abs() as usize > seen[k] {
                    Some(format!(
                        "face refers to {what} {x} but only {} come before it ({word:?})",
                        seen[k]
                    ))
                } else {
                    None
                };
                if let Some(why) = why {
                    return Some((number + 1, why));
                }
            }
        }
    }
    None
}
