//! Port cards: what a variant named after another renderer takes from that
//! renderer's source, and where.
//!
//! A lesson that ports a renderer's default (LearnOpenGL, the wgpu example,
//! Bevy, Filament, Godot, three.js) keeps one card per port, in one place
//! per lesson (`lessons/lesson_NN/port_cards.rs`): the repository, each
//! file read with its commit and lines, every constant and formula the port
//! takes from there as the source writes it (tap positions, counts, radii
//! and their units, the depth convention, the map size, the blur, the bias),
//! and every way the port cannot follow its source here (a renderer's TAA,
//! its atlas), each with why.
//!
//! The card is a transcription of the source; the port is code. They are
//! written apart on purpose, and a test per lesson checks one against the
//! other (`tests/port_cards.rs`): a port whose constant drifts from its
//! card, or a card that drifts from its port, fails. The book's "where each
//! port departs" tables are generated from the cards.

/// One file of the renderer's repository, read at one commit.
#[derive(Clone, Copy, Debug)]
pub struct Source {
    pub file: &'static str,
    /// The full 40-digit commit the file was read at.
    pub commit: &'static str,
    /// The repository the commit is in, where it is not the card's own (a
    /// mirror of a release): `owner/name`.
    pub repository: Option<&'static str>,
}

/// A value as the source writes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Num(f64),
    /// A list: taps, weights, offsets (flattened pairs for 2D points).
    List(&'static [f64]),
    /// A formula, an enum's choice, a convention: the source's words.
    Text(&'static str),
}

/// The unit of a card's tap counts (`unit: TAPS_UNIT`).
pub const TAPS_UNIT: &str = "taps"; // not a counter: a unit

/// One constant or formula a port takes from its source.
#[derive(Clone, Copy, Debug)]
pub struct Constant {
    /// The name the source gives it (`PCSS_SHADOW_FILTER_TAP_COUNT`), or
    /// what it is where the source has no name.
    pub name: &'static str,
    pub value: Value,
    /// Its unit where it has one ("texels", "m", "depth units", "taps").
    pub unit: &'static str,
    /// Index into the card's [`PortCard::sources`].
    pub source: usize,
    /// The lines of that file it is read from: "312" or "305-330".
    pub lines: &'static str,
}

/// A way the port cannot do what its source does, here.
#[derive(Clone, Copy, Debug)]
pub struct Departure {
    pub what: &'static str,
    pub why: &'static str,
}

/// Whether a port is what its renderer runs unless told otherwise, or
/// something a user turns on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Role {
    /// The renderer's default (a tutorial's own listing counts as one).
    Default,
    /// An option, with the setting that turns it on.
    Option(&'static str),
}

impl Role {
    /// "default", or "option: the setting".
    pub fn text(self) -> String {
        match self {
            Role::Default => "default".into(),
            Role::Option(setting) => format!("option: {setting}"),
        }
    }
}

/// The card of one port: one variant of one lesson.
#[derive(Clone, Copy, Debug)]
pub struct PortCard {
    /// The variant's `--variant` name.
    pub variant: &'static str,
    pub renderer: &'static str,
    /// Its renderer's default, or an option (and its setting).
    pub role: Role,
    /// `owner/name`.
    pub repository: &'static str,
    pub sources: &'static [Source],
    pub constants: &'static [Constant],
    pub departures: &'static [Departure],
}

impl PortCard {
    /// The constant named `name`; panics if the card has none (a test's
    /// question about a card it must hold).
    pub fn constant(&self, name: &str) -> &Constant {
        self.constants
            .iter()
            .find(|c| c.name == name)
            .unwrap_or_else(|| panic!("{}'s card has no constant {name}", self.variant))
    }

    /// The number `name` holds; panics if it is not a number.
    pub fn num(&self, name: &str) -> f64 {
        match self.constant(name).value {
            Value::Num(x) => x,
            v => panic!("{}'s {name} is not a number: {v:?}", self.variant),
        }
    }

    /// The list `name` holds; panics if it is not a list.
    pub fn list(&self, name: &str) -> &'static [f64] {
        match self.constant(name).value {
            Value::List(x) => x,
            v => panic!("{}'s {name} is not a list: {v:?}", self.variant),
        }
    }

    /// The text `name` holds; panics if it is not text.
    pub fn text(&self, name: &str) -> &'static str {
        match self.constant(name).value {
            Value::Text(x) => x,
            v => panic!("{}'s {name} is not text: {v:?}", self.variant),
        }
    }

    /// Where constant `c` comes from: `file@commit7:lines`.
    pub fn cite(&self, c: &Constant) -> String {
        let s = &self.sources[c.source];
        format!("{}@{}:{}", s.file, &s.commit[..7], c.lines)
    }

    /// What is wrong with the card itself: an empty field, a commit that is
    /// not 40 hex digits, a constant that names no source.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        let v = self.variant;
        if self.renderer.is_empty() || !self.repository.contains('/') {
            out.push(format!("{v}: renderer or repository missing"));
        }
        if self.sources.is_empty() || self.constants.is_empty() {
            out.push(format!("{v}: a card needs a source and a constant"));
        }
        if self.role == Role::Option("") {
            out.push(format!(
                "{v}: an option without the setting that turns it on"
            ));
        }
        for s in self.sources {
            let hex = s.commit.len() == 40 && s.commit.chars().all(|c| c.is_ascii_hexdigit());
            let repository = s.repository.is_none_or(|r| r.contains('/'));
            if !hex || s.file.is_empty() || !repository {
                out.push(format!("{v}: source {} at {:?}", s.file, s.commit));
            }
        }
        for c in self.constants {
            if c.source >= self.sources.len() || c.lines.is_empty() || c.name.is_empty() {
                out.push(format!("{v}: constant {:?} has no source or lines", c.name));
            }
        }
        for d in self.departures {
            if d.what.is_empty() || d.why.is_empty() {
                out.push(format!("{v}: a departure without what or why"));
            }
        }
        out
    }
}

/// A value as a table cell: numbers as written, lists by their count and
/// first entries.
pub fn value_text(v: &Value) -> String {
    match v {
        Value::Num(x) => format!("{x}"),
        Value::Text(t) => t.to_string(),
        Value::List(xs) => {
            let head: Vec<String> = xs.iter().take(4).map(|x| format!("{x}")).collect();
            let more = if xs.len() > 4 { ", …" } else { "" };
            format!("{} values: {}{more}", xs.len(), head.join(", "))
        }
    }
}

/// The "where each port departs" tables of a chapter, in markdown: one row
/// per departure (variant, renderer, what the port cannot do here, why),
/// then one row per card with the files it was read from, as
/// `file@commit7`. A card without departures gets a row that says so.
pub fn departures_table(cards: &[PortCard]) -> String {
    let cell = |t: &str| t.replace('|', "\\|").replace('\n', " ");
    let mut out = String::from(
        "| variant | renderer | what the port cannot do here | why |\n| --- | --- | --- | --- |\n",
    );
    for c in cards {
        if c.departures.is_empty() {
            out += &format!("| `{}` | {} | nothing | |\n", c.variant, cell(c.renderer));
        }
        for d in c.departures {
            out += &format!(
                "| `{}` | {} | {} | {} |\n",
                c.variant,
                cell(c.renderer),
                cell(d.what),
                cell(d.why)
            );
        }
    }
    out += "\n| variant | default or option | repository | read at |\n| --- | --- | --- | --- |\n";
    for c in cards {
        let files: Vec<String> = c
            .sources
            .iter()
            .map(|s| {
                let mirror = s.repository.map_or(String::new(), |r| format!(" ({r})"));
                format!(
                    "`{}@{}`{mirror}",
                    s.file,
                    &s.commit[..s.commit.len().min(7)]
                )
            })
            .collect();
        out += &format!(
            "| `{}` | {} | {} | {} |\n",
            c.variant,
            cell(&c.role.text()),
            cell(c.repository),
            files.join("<br>")
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const CARD: PortCard = PortCard {
        variant: "x",
        renderer: "R",
        role: Role::Default,
        repository: "o/r",
        sources: &[Source {
            file: "a.glsl",
            commit: "0123456789abcdef0123456789abcdef01234567",
            repository: None,
        }],
        constants: &[Constant {
            name: "TAPS",
            value: Value::Num(16.0),
            unit: TAPS_UNIT,
            source: 0,
            lines: "12",
        }],
        departures: &[],
    };

    #[test]
    fn a_whole_card_has_no_problems_and_a_broken_one_has() {
        assert!(CARD.problems().is_empty());
        assert_eq!(CARD.num("TAPS"), 16.0);
        assert_eq!(CARD.cite(&CARD.constants[0]), "a.glsl@0123456:12");
        let short = PortCard {
            sources: &[Source {
                file: "a.glsl",
                commit: "0123456",
                repository: None,
            }],
            ..CARD
        };
        assert_eq!(short.problems().len(), 1);
        const ORPHAN: &[Constant] = &[Constant {
            source: 1,
            name: "TAPS",
            value: Value::Num(16.0),
            unit: TAPS_UNIT,
            lines: "12",
        }];
        let orphan = PortCard {
            constants: ORPHAN,
            ..CARD
        };
        assert_eq!(orphan.problems().len(), 1);
        let unset = PortCard {
            role: Role::Option(""),
            ..CARD
        };
        assert_eq!(unset.problems().len(), 1);
    }

    #[test]
    fn the_departures_table_has_a_row_per_departure_and_per_card() {
        let card = PortCard {
            departures: &[Departure {
                what: "a | b",
                why: "c",
            }],
            ..CARD
        };
        let t = departures_table(&[card, CARD]);
        assert!(t.contains("| `x` | R | a \\| b | c |"), "{t}");
        assert!(t.contains("| `x` | R | nothing | |"), "{t}");
        assert!(
            t.contains("| `x` | default | o/r | `a.glsl@0123456` |"),
            "{t}"
        );
        let option = PortCard {
            role: Role::Option("Light.soft = true"),
            ..CARD
        };
        let t = departures_table(&[option]);
        assert!(
            t.contains("| `x` | option: Light.soft = true | o/r |"),
            "{t}"
        );
    }
}
