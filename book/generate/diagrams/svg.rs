//! The hand-built SVG every diagram is drawn with: a canvas ([`Svg`]) of
//! lines, shapes and texts, the stroke and fill styles, and the text width
//! estimate its layouts (and the tests' fit check) rely on.

use std::fmt::Write as _;

use common::glam::DVec3;

pub(crate) type P = (f64, f64);

/// Estimated width of one line of text: 0.6 em a character, generous for
/// sans-serif, so that what fits by this estimate fits when rendered.
pub(crate) fn text_width(s: &str, size: f64) -> f64 {
    0.6 * size * s.chars().count() as f64
}

/// The estimated horizontal extent of a text drawn at `x` with `anchor`.
pub(crate) fn text_span(x: f64, size: f64, anchor: &str, s: &str) -> (f64, f64) {
    let w = text_width(s, size);
    match anchor {
        "start" => (x, x + w),
        "end" => (x - w, x),
        _ => (x - w / 2.0, x + w / 2.0),
    }
}

/// Greedy word wrap of `s` into lines no wider than `width` (estimated).
pub(crate) fn wrap(s: &str, size: f64, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in s.split_whitespace() {
        match lines.last_mut() {
            Some(l) if text_width(l, size) + text_width(&format!(" {word}"), size) <= width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Two attributes from a point: `x="…" y="…"`.
pub(crate) fn xy(x: &str, y: &str, p: P) -> String {
    format!(r#"{x}="{:.2}" {y}="{:.2}""#, p.0, p.1)
}

/// A vector as the diagrams print it: `(−1, 0, 0.5)`, true minus signs.
pub(crate) fn vec_text(v: DVec3) -> String {
    let c = |x: f64| {
        if x < 0.0 {
            format!("−{}", -x)
        } else {
            format!("{}", x + 0.0)
        }
    };
    format!("({}, {}, {})", c(v.x), c(v.y), c(v.z))
}

/// A hand-built SVG: white background, a title, then whatever is drawn.
pub(crate) struct Svg {
    pub(crate) w: f64,
    pub(crate) h: f64,
    body: String,
}

pub(crate) const INK: &str = r##"stroke="#222" stroke-width="1.5" fill="none""##;

/// A stroke style: colour, width, and a dash pattern ("" for none).
pub(crate) fn stroke(colour: &str, width: f64, dash: &str) -> String {
    format!(r#"stroke="{colour}" stroke-width="{width}" stroke-dasharray="{dash}" fill="none""#)
}

pub(crate) fn fill(colour: &str, edge: &str) -> String {
    format!(r#"fill="{colour}" stroke="{edge}" stroke-width="1.5""#)
}

pub(crate) fn add(p: P, dx: f64, dy: f64) -> P {
    (p.0 + dx, p.1 + dy)
}

impl Svg {
    pub(crate) fn new(w: f64, h: f64, title: &str) -> Svg {
        let mut s = Svg {
            w,
            h,
            body: String::new(),
        };
        s.text((w / 2.0, 24.0), 17.0, "middle", title);
        s
    }
    pub(crate) fn line(&mut self, a: P, b: P, style: &str) {
        let (a, b) = (xy("x1", "y1", a), xy("x2", "y2", b));
        let _ = writeln!(self.body, "<line {a} {b} {style}/>");
    }
    pub(crate) fn arrow(&mut self, a: P, b: P, colour: &str) {
        let style = stroke(colour, 1.5, "") + r#" marker-end="url(#arrow)""#;
        self.line(a, b, &style);
    }
    pub(crate) fn poly(&mut self, pts: &[P], closed: bool, style: &str) {
        let pts: Vec<String> = pts
            .iter()
            .map(|p| format!("{:.2},{:.2}", p.0, p.1))
            .collect();
        let tag = if closed { "polygon" } else { "polyline" };
        let _ = writeln!(self.body, r#"<{tag} points="{}" {style}/>"#, pts.join(" "));
    }
    pub(crate) fn rect(&mut self, at: P, size: P, style: &str) {
        let (at, size) = (xy("x", "y", at), xy("width", "height", size));
        let _ = writeln!(self.body, "<rect {at} {size} {style}/>");
    }
    pub(crate) fn circle(&mut self, c: P, r: f64, style: &str) {
        let c = xy("cx", "cy", c);
        let _ = writeln!(self.body, r#"<circle {c} r="{r:.2}" {style}/>"#);
    }
    pub(crate) fn text(&mut self, at: P, size: f64, anchor: &str, s: &str) {
        let s = s.replace('&', "&amp;").replace('<', "&lt;");
        let at = xy("x", "y", at);
        let attrs = format!(r#"{at} font-size="{size:.0}" text-anchor="{anchor}""#);
        let _ = writeln!(self.body, "<text {attrs}>{s}</text>");
    }
    /// Lines one under another; returns the baseline a next line would take.
    pub(crate) fn texts(&mut self, at: P, size: f64, anchor: &str, lines: &[String]) -> f64 {
        for (i, l) in lines.iter().enumerate() {
            self.text((at.0, at.1 + (size + 5.0) * i as f64), size, anchor, l);
        }
        at.1 + (size + 5.0) * lines.len() as f64
    }
    /// `s` wrapped to `width` and drawn as lines; returns the next baseline.
    pub(crate) fn para(&mut self, at: P, size: f64, anchor: &str, width: f64, s: &str) -> f64 {
        self.texts(at, size, anchor, &wrap(s, size, width))
    }
    /// The document; the white background is drawn here, so that `h` may
    /// be set once the content's height is known.
    pub(crate) fn finish(mut self) -> String {
        let body = std::mem::take(&mut self.body);
        self.rect((0.0, 0.0), (self.w, self.h), r##"fill="#fff""##);
        self.body += &body;
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="sans-serif">"#,
                "\n<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" markerHeight=\"7\" orient=\"auto\">",
                "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#222\"/></marker></defs>\n{body}</svg>\n"
            ),
            w = self.w,
            h = self.h,
            body = self.body
        )
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use std::collections::HashMap;

    use super::*;

    /// The value of attribute `name` in a tag's attribute text.
    fn attr(tag: &str, name: &str) -> f64 {
        let key = format!(" {name}=\"");
        let at = tag.find(&key).map(|i| i + key.len()).expect(name);
        tag[at..at + tag[at..].find('"').unwrap()]
            .parse()
            .expect(name)
    }

    /// The number that follows `key` in `text` (digits, a point, an
    /// exponent), for the tests that read a diagram's printed values.
    pub(crate) fn after(text: &str, key: &str) -> f64 {
        let at = text
            .find(key)
            .unwrap_or_else(|| panic!("no {key:?} in {text:?}"))
            + key.len();
        let num: String = (text[at..].chars())
            .take_while(|c| c.is_ascii_digit() || ".e-".contains(*c))
            .collect();
        num.parse().unwrap_or_else(|_| panic!("{key:?}: {num:?}"))
    }

    /// The attributes of every `<tag …/>` element of `svg`, by name: what
    /// the geometry tests read back from a drawing.
    pub(crate) fn elements(svg: &str, tag: &str) -> Vec<HashMap<String, String>> {
        let open = format!("<{tag} ");
        svg.split(&open)
            .skip(1)
            .map(|part| {
                let attrs = &part[..part.find('>').unwrap()];
                attrs
                    .split('"')
                    .collect::<Vec<_>>()
                    .chunks_exact(2)
                    .map(|kv| {
                        let key = kv[0].trim().trim_end_matches('=');
                        (key.to_string(), kv[1].to_string())
                    })
                    .collect()
            })
            .collect()
    }

    /// Whether an element's attribute `name` is `value`.
    pub(crate) fn is(e: &HashMap<String, String>, name: &str, value: &str) -> bool {
        e.get(name).is_some_and(|v| v == value)
    }

    /// An element's numeric attribute.
    pub(crate) fn number(e: &HashMap<String, String>, name: &str) -> f64 {
        e[name].parse().expect(name)
    }

    /// Every text of `svg`: (x, y, its words, unescaped).
    pub(crate) fn texts(svg: &str) -> Vec<(f64, f64, String)> {
        let words = svg.split("<text ").skip(1).map(|part| {
            let text = part.split_once('>').unwrap().1;
            let text = text.split_once("</text>").unwrap().0;
            text.replace("&lt;", "<").replace("&amp;", "&")
        });
        (elements(svg, "text").iter().zip(words))
            .map(|(e, w)| (number(e, "x"), number(e, "y"), w))
            .collect()
    }

    /// Every text of `svg` lies inside its canvas by the same width
    /// estimate the layout uses, and no two texts' boxes overlap.
    pub(crate) fn assert_texts_fit(name: &str, svg: &str) {
        let svg_tag = &svg[..svg.find('>').unwrap()];
        let (w, h) = (attr(svg_tag, "width"), attr(svg_tag, "height"));
        let mut boxes: Vec<(f64, f64, f64, f64, String)> = Vec::new();
        for part in svg.split("<text").skip(1) {
            let (tag, rest) = part.split_once('>').unwrap();
            let text = rest.split_once("</text>").unwrap().0;
            let text = text.replace("&lt;", "<").replace("&amp;", "&");
            let anchor = tag
                .split("text-anchor=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next();
            let (x, y, size) = (attr(tag, "x"), attr(tag, "y"), attr(tag, "font-size"));
            let (x0, x1) = text_span(x, size, anchor.unwrap(), &text);
            let (y0, y1) = (y - 0.8 * size, y + 0.25 * size);
            assert!(
                x0 >= 0.0 && x1 <= w,
                "{name}: {text:?} spans x {x0:.0}..{x1:.0} of {w}"
            );
            assert!(
                y0 >= 0.0 && y1 <= h,
                "{name}: {text:?} spans y {y0:.0}..{y1:.0} of {h}"
            );
            for (a0, a1, b0, b1, other) in &boxes {
                let apart = x1 <= *a0 || *a1 <= x0 || y1 <= *b0 || *b1 <= y0;
                assert!(apart, "{name}: {text:?} overlaps {other:?}");
            }
            boxes.push((x0, x1, y0, y1, text));
        }
    }
}
