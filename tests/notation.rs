//! One symbol, one meaning, in each chapter. A chapter's math opens with
//! its notation list:
//!
//! ```text
//! **Notation.**
//!
//! - $\hat d$: the light's direction, towards the scene (unit vector)
//! - $s_x$, $s_y$: a texel's width and height in the scene (m)
//! ```
//!
//! Fails, naming the page and the symbol, when a page of [`PAGES`] that
//! has math:
//!
//! - has no notation list, or (a lesson chapter) uses a symbol before it;
//! - uses a symbol its list lacks. A listed symbol covers its components
//!   (`$\hat d$` covers `$\hat d_y$`), and a family indexed by `i`, `j`,
//!   `k` or `n` covers its members (`$z_i$` covers `$z_0$` and `$z_{i+1}$`);
//! - lists a symbol twice, or lists one it never uses;
//! - lists two symbols that differ only by an accent (`$f$` and `$\hat f$`):
//!   one letter, one thing;
//! - gives an entry no meaning, or no unit in parentheses at its end.
//!
//! A symbol is a letter or a Greek letter with its accents (`\hat`,
//! `\bar`, `\tilde`, `\mathbf`, ...), its subscript and its primes; words in
//! `\text{}` or `\operatorname{}`, functions (`\tan`) and operators are not.
//!
//! Pure std, no GPU. The reader is tested on in-memory text first.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::PathBuf;

/// The chapters whose math must have a notation list (when they have math).
const PAGES: &[&str] = &[
    "introduction.md",
    "using.md",
    "reference.md",
    "lesson_01.md",
    "lesson_02.md",
    "lesson_03.md",
    "lesson_04.md",
    "lesson_05.md",
    "lesson_06.md",
    "lesson_07.md",
    "lesson_08.md",
    "lesson_09.md",
    "lesson_10.md",
    "choosing.md",
    "scaling.md",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

const ACCENTS: &[&str] = &[
    "hat",
    "bar",
    "tilde",
    "vec",
    "mathbf",
    "boldsymbol",
    "dot",
    "ddot",
    "overline",
    "widehat",
    "widetilde",
];
const GREEK: &[&str] = &[
    "alpha",
    "beta",
    "gamma",
    "Gamma",
    "delta",
    "Delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "Theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "Lambda",
    "mu",
    "nu",
    "xi",
    "Xi",
    "rho",
    "varrho",
    "sigma",
    "Sigma",
    "tau",
    "upsilon",
    "phi",
    "Phi",
    "varphi",
    "chi",
    "psi",
    "Psi",
    "omega",
    "Omega",
    "ell",
];
/// Commands whose braced argument is text or a name, not math.
const TEXT_ARG: &[&str] = &[
    "text",
    "textrm",
    "textit",
    "textbf",
    "mathrm",
    "mathit",
    "mathbb",
    "mathcal",
    "operatorname",
    "begin",
    "end",
    "label",
    "tag",
    "mbox",
    "hbox",
    "color",
];

/// A symbol: accents, base letter (or Greek name), primes, subscript.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Symbol {
    accents: Vec<String>,
    base: String,
    sub: Option<String>,
}

impl Symbol {
    fn key(&self) -> String {
        let mut s = String::new();
        for a in &self.accents {
            s += &format!("\\{a} ");
        }
        s += &self.base;
        if let Some(sub) = &self.sub {
            s += &format!("_{sub}");
        }
        s
    }
    fn without_accents(&self) -> String {
        Symbol {
            accents: Vec::new(),
            ..self.clone()
        }
        .key()
    }
}

struct Reader<'a> {
    c: Vec<char>,
    i: usize,
    out: &'a mut Vec<Symbol>,
}

impl Reader<'_> {
    fn peek(&self) -> Option<char> {
        self.c.get(self.i).copied()
    }
    fn spaces(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.i += 1;
        }
    }
    /// The command's name after a backslash at `i` (empty for `\,`).
    fn command(&mut self) -> String {
        self.i += 1;
        let start = self.i;
        while self.peek().is_some_and(|c| c.is_ascii_alphabetic()) {
            self.i += 1;
        }
        if self.i == start {
            self.i += 1; // `\,` `\;` `\{` `\\`
        }
        self.c[start..self.i].iter().collect()
    }
    /// The braced group at `i` (after spaces), its text; `None` if none.
    fn group(&mut self) -> Option<String> {
        self.spaces();
        if self.peek() != Some('{') {
            return None;
        }
        let mut depth = 0;
        let start = self.i;
        while let Some(c) = self.peek() {
            self.i += 1;
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(self.c[start + 1..self.i - 1].iter().collect());
                    }
                }
                _ => {}
            }
        }
        Some(self.c[start + 1..].iter().collect())
    }
    /// One argument: a group, a command (with its group), or a character.
    fn argument(&mut self) -> String {
        self.spaces();
        match self.peek() {
            Some('{') => self.group().unwrap_or_default(),
            Some('\\') => {
                let name = self.command();
                match self.group() {
                    Some(g) if TEXT_ARG.contains(&name.as_str()) => g,
                    Some(g) => format!("\\{name}{{{g}}}"),
                    None => format!("\\{name}"),
                }
            }
            Some(c) => {
                self.i += 1;
                c.to_string()
            }
            None => String::new(),
        }
    }
    /// Primes, a subscript and superscripts after a symbol.
    fn after(&mut self, mut s: Symbol) {
        let mut exponents = Vec::new();
        loop {
            self.spaces();
            match self.peek() {
                Some('\'') => {
                    self.i += 1;
                    s.base.push('\'');
                }
                Some('_') if s.sub.is_none() => {
                    self.i += 1;
                    s.sub = Some(normal_sub(&self.argument()));
                }
                Some('^') => {
                    self.i += 1;
                    self.spaces();
                    let grouped = self.peek() == Some('{');
                    let sup = self.argument();
                    // A braced exponent is math (`e^{-x}`); `^2`, `^T` are not symbols.
                    if grouped {
                        exponents.push(sup);
                    }
                }
                _ => break,
            }
        }
        self.out.push(s);
        for e in exponents {
            read(&e, self.out);
        }
    }
    fn run(&mut self) {
        while let Some(c) = self.peek() {
            if c == '\\' {
                let name = self.command();
                if TEXT_ARG.contains(&name.as_str()) {
                    self.group();
                } else if name == "def" {
                    self.argument();
                    self.group();
                } else if ACCENTS.contains(&name.as_str()) {
                    let arg = self.argument();
                    let mut inner = Vec::new();
                    read(&arg, &mut inner);
                    if let Some(mut s) = inner.into_iter().next() {
                        s.accents.insert(0, name);
                        self.after(s);
                    }
                } else if GREEK.contains(&name.as_str()) {
                    self.after(Symbol {
                        accents: Vec::new(),
                        base: name,
                        sub: None,
                    });
                }
            } else if c.is_alphabetic() {
                self.i += 1;
                self.after(Symbol {
                    accents: Vec::new(),
                    base: c.to_string(),
                    sub: None,
                });
            } else if c == '_' || c == '^' {
                self.i += 1;
                self.argument();
            } else {
                self.i += 1;
            }
        }
    }
}

/// A subscript as a key: `{\text{map}}` → `map`, `{ i + 1 }` → `i+1`.
fn normal_sub(s: &str) -> String {
    let mut t = s.to_string();
    for w in ["\\text", "\\mathrm", "\\operatorname", "\\textrm"] {
        t = t.replace(w, "");
    }
    t.chars()
        .filter(|c| !c.is_whitespace() && !['{', '}', '\\'].contains(c))
        .collect()
}

/// The symbols of one math span, in order.
fn read(math: &str, out: &mut Vec<Symbol>) {
    Reader {
        c: math.chars().collect(),
        i: 0,
        out,
    }
    .run();
}

fn symbols(math: &str) -> Vec<Symbol> {
    let mut out = Vec::new();
    read(math, &mut out);
    out
}

/// The blanks that stand for `c`: as many bytes, so that an offset into
/// the blanked text is the same offset into the page (the notation list's
/// place is found in the page itself).
fn blank(c: char) -> String {
    if c == '\n' {
        "\n".into()
    } else {
        " ".repeat(c.len_utf8())
    }
}

/// `text` with code blocks, inline code and HTML comments blanked (line
/// breaks and byte offsets kept), so that `$` inside them is not math.
fn blank_code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut fenced = false;
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            out.extend(line.chars().map(blank));
            continue;
        }
        if fenced {
            out.extend(line.chars().map(blank));
            continue;
        }
        let mut in_code = false;
        for c in line.chars() {
            if c == '`' {
                in_code = !in_code;
                out.push(' ');
            } else if in_code {
                out.push_str(&blank(c));
            } else {
                out.push(c);
            }
        }
    }
    // Comments (claims, markers) may span lines.
    let mut s = String::with_capacity(out.len());
    let mut rest = out.as_str();
    while let Some(a) = rest.find("<!--") {
        let b = rest[a..].find("-->").map_or(rest.len(), |b| a + b + 3);
        s.push_str(&rest[..a]);
        s.extend(rest[a..b].chars().map(blank));
        rest = &rest[b..];
    }
    s.push_str(rest);
    debug_assert_eq!(s.len(), text.len());
    s
}

/// Every math span of `text`: (byte offset, content).
fn math_spans(text: &str) -> Vec<(usize, String)> {
    let t = blank_code(text);
    let b = t.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'\\' {
            i += 2;
            continue;
        }
        if b[i] != b'$' {
            i += 1;
            continue;
        }
        let display = b.get(i + 1) == Some(&b'$');
        let open = if display { 2 } else { 1 };
        let close = if display { "$$" } else { "$" };
        let Some(len) = t[i + open..].find(close) else {
            break;
        };
        let body = &t[i + open..i + open + len];
        if display || !body.contains('\n') {
            out.push((i, body.to_string()));
        }
        i += open + len + open;
    }
    out
}

/// A page's notation list: (byte range, entries), where an entry is
/// (its symbols, its meaning, its line).
struct List {
    start: usize,
    end: usize,
    entries: Vec<(Vec<Symbol>, String, usize)>,
}

fn notation_list(text: &str) -> Option<List> {
    let mut offset = 0;
    let mut start = None;
    let mut entries = Vec::new();
    let mut end = 0;
    for (n, line) in text.split_inclusive('\n').enumerate() {
        let t = line.trim();
        let at = offset;
        offset += line.len();
        match start {
            None => {
                if t == "**Notation.**" || (t.starts_with('#') && t.ends_with("Notation")) {
                    start = Some(at);
                }
            }
            Some(_) => {
                if let Some(item) = t.strip_prefix("- ") {
                    entries.push((item.to_string(), n + 1));
                    end = offset;
                } else if !t.is_empty() && !entries.is_empty() && line.starts_with("  ") {
                    // An entry wrapped onto the next line.
                    let last = entries.last_mut().expect("an entry");
                    last.0 = format!("{} {t}", last.0);
                    end = offset;
                } else if !(t.is_empty() && entries.is_empty()) {
                    // The first blank line after the entries, or any other text, ends it.
                    break;
                }
            }
        }
    }
    let start = start?;
    let entries = entries
        .into_iter()
        .map(|(item, line)| {
            // The symbols: the math spans before the first `:` outside math.
            let mut syms = Vec::new();
            let mut rest = item.as_str();
            loop {
                let r = rest.trim_start_matches([' ', ',']);
                let r = r.strip_prefix("and ").unwrap_or(r);
                let Some(after) = r.strip_prefix('$') else {
                    rest = r;
                    break;
                };
                let Some(close) = after.find('$') else {
                    rest = r;
                    break;
                };
                syms.extend(symbols(&after[..close]));
                rest = &after[close + 1..];
            }
            let meaning = rest.strip_prefix(':').unwrap_or("").trim().to_string();
            (syms, meaning, line)
        })
        .collect();
    Some(List {
        start,
        end,
        entries,
    })
}

/// Whether `listed` covers `used`: the same, its component, or its family.
fn covers(listed: &Symbol, used: &Symbol) -> bool {
    if listed == used {
        return true;
    }
    if listed.accents != used.accents || listed.base != used.base {
        return false;
    }
    match (&listed.sub, &used.sub) {
        (None, Some(s)) => ["x", "y", "z", "w"].contains(&s.as_str()),
        (Some(index), Some(s)) if ["i", "j", "k", "n"].contains(&index.as_str()) => {
            s.chars().all(|c| c.is_ascii_digit()) || (s.contains(index.as_str()) && s.len() > 1)
        }
        _ => false,
    }
}

/// What is wrong with one page's notation, one line each.
fn problems(text: &str, lesson: bool) -> Vec<String> {
    let spans = math_spans(text);
    if spans.is_empty() {
        return Vec::new();
    }
    let Some(list) = notation_list(text) else {
        return vec![
            "has math but no notation list (`**Notation.**` and one `- $symbol$: meaning (unit)` a line)".into(),
        ];
    };
    let mut out = Vec::new();
    let mut listed: BTreeMap<String, (Symbol, usize)> = BTreeMap::new();
    for (syms, meaning, line) in &list.entries {
        if syms.is_empty() {
            out.push(format!("line {line}: an entry that names no symbol"));
        }
        if meaning.is_empty() || !meaning.ends_with(')') {
            out.push(format!(
                "line {line}: an entry needs a meaning and its unit in parentheses at the end"
            ));
        }
        for s in syms {
            if let Some((_, first)) = listed.insert(s.key(), (s.clone(), *line)) {
                out.push(format!(
                    "line {line}: ${}$ listed twice (first on line {first})",
                    s.key()
                ));
            }
        }
    }
    let mut by_letter: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (k, (s, _)) in &listed {
        by_letter
            .entry(s.without_accents())
            .or_default()
            .insert(k.clone());
    }
    for (letter, keys) in &by_letter {
        if keys.len() > 1 {
            let all: Vec<&str> = keys.iter().map(String::as_str).collect();
            out.push(format!(
                "{} are one letter ({letter}) with two meanings: rename one",
                all.join(" and ")
            ));
        }
    }
    let mut used = BTreeSet::new();
    let mut missing = BTreeSet::new();
    for (at, math) in &spans {
        let in_list_symbols = *at >= list.start && *at < list.end && {
            // The entry's own symbols are its names, not uses.
            let line_start = text[..*at].rfind('\n').map_or(0, |i| i + 1);
            let before = &text[line_start..*at];
            before.trim_start().starts_with("- ") && !before.contains(':')
        };
        if in_list_symbols {
            continue;
        }
        if lesson && *at < list.start {
            let line = text[..*at].lines().count();
            out.push(format!(
                "line {line}: ${math}$ comes before the notation list"
            ));
        }
        for s in symbols(math) {
            // The symbol itself first (`$z_w$` listed beside `$z$`), then
            // what covers it.
            let exact = listed.get(&s.key());
            match exact.or_else(|| listed.values().find(|(l, _)| covers(l, &s))) {
                Some((l, _)) => {
                    used.insert(l.key());
                }
                None => {
                    missing.insert(s.key());
                }
            }
        }
    }
    for m in missing {
        out.push(format!("${m}$ is used but not in the notation list"));
    }
    for (k, (_, line)) in &listed {
        if !used.contains(k) {
            out.push(format!("line {line}: ${k}$ is listed but never used"));
        }
    }
    out
}

fn keys(math: &str) -> Vec<String> {
    symbols(math).iter().map(Symbol::key).collect()
}

#[test]
fn the_reader_finds_symbols_and_not_words() {
    assert_eq!(
        keys(r"d_r \le d_{\text{map}}(u, v)"),
        ["d_r", "d_map", "u", "v"]
    );
    assert_eq!(keys(r"\hat f = \hat d"), ["\\hat f", "\\hat d"]);
    assert_eq!(keys(r"\lvert \hat{d}_y \rvert > 0.99"), ["\\hat d_y"]);
    assert_eq!(
        keys(r"\tan\theta \cdot \operatorname{normalize}(x)"),
        ["theta", "x"]
    );
    assert_eq!(
        keys(r"w_\text{penumbra} = R\,\frac{d_r - d_b}{d_r}"),
        ["w_penumbra", "R", "d_r", "d_b", "d_r"]
    );
    assert_eq!(
        keys(r"M^T x^2 e^{-\lambda t}"),
        ["M", "x", "e", "lambda", "t"]
    );
    assert_eq!(
        keys(r"\hat{\mathbf n}' z_{i+1}"),
        ["\\hat \\mathbf n'", "z_i+1"]
    );
    assert_eq!(
        keys(r"\def\arraystretch{1.6}\begin{pmatrix} a \end{pmatrix}"),
        ["a"]
    );
}

#[test]
fn the_checker_finds_what_is_wrong() {
    let good = "Intro.\n\n**Notation.**\n\n- $f$: the far distance (m)\n- $z_i$: a split (m)\n\nThen $f > z_0 + z_{i+1}$.\n";
    assert!(
        problems(good, true).is_empty(),
        "{:?}",
        problems(good, true)
    );
    let missing = good.replace("Then $f", "Then $g + f");
    assert!(problems(&missing, true)[0].contains("$g$ is used"));
    let twice = good.replace("- $z_i$", "- $f$: again (m)\n- $z_i$");
    assert!(problems(&twice, true)
        .iter()
        .any(|p| p.contains("listed twice")));
    let accent =
        good.replace("- $z_i$", "- $\\hat f$: forward (unit vector)\n- $z_i$") + "And $\\hat f$.\n";
    assert!(problems(&accent, true)
        .iter()
        .any(|p| p.contains("one letter")));
    // A listed symbol is matched before a listed base that covers it.
    let component = good.replace(
        "- $z_i$",
        "- $z$: depth (m)\n- $z_w$: window depth (m)\n- $z_i$",
    ) + "And $z + z_w$.\n";
    assert!(
        problems(&component, true).is_empty(),
        "{:?}",
        problems(&component, true)
    );
    let unused = good.replace("- $z_i$", "- $q$: nothing (m)\n- $z_i$");
    assert!(problems(&unused, true)
        .iter()
        .any(|p| p.contains("never used")));
    let no_unit = good.replace("the far distance (m)", "the far distance");
    assert!(problems(&no_unit, true).iter().any(|p| p.contains("unit")));
    // Code before the list (fenced, inline, with wide characters) keeps the
    // list's place: its entries are names, not uses before it.
    let coded = format!(
        "```rust\nlet x = 1; // \u{2212}\u{00d7}\n```\n`\u{2212}` <!-- \u{00d7} -->\n{good}"
    );
    assert!(
        problems(&coded, true).is_empty(),
        "{:?}",
        problems(&coded, true)
    );
    let early = format!("Before $f$.\n{good}");
    assert!(problems(&early, true)
        .iter()
        .any(|p| p.contains("before the notation")));
    assert!(problems(&early, false)
        .iter()
        .all(|p| !p.contains("before the notation")));
    assert!(problems("No math here, `$HOME` is code.\n", true).is_empty());
    assert!(problems("Math $x$ but no list.\n", true)[0].contains("no notation list"));
}

#[test]
fn every_chapter_lists_its_symbols_once() {
    let src = root().join("book/src");
    let mut failures = Vec::new();
    for page in PAGES {
        let Ok(text) = fs::read_to_string(src.join(page)) else {
            continue;
        };
        let lesson = page.starts_with("lesson_");
        for p in problems(&text, lesson) {
            failures.push(format!("book/src/{page}: {p}"));
        }
    }
    assert!(
        failures.is_empty(),
        "notation (tests/notation.rs says what a list holds):\n  {}",
        failures.join("\n  ")
    );
}
