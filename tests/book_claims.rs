//! The book's sentences say what its records say. Fails, with the file and
//! line, when:
//!
//! - a claim (`<!--claim: LEFT OP RIGHT-->`, see `book/generate/claims.rs`)
//!   is false on the committed records, or cannot be read;
//! - a sentence of a lesson, the choosing or the scaling chapter compares
//!   (more, fewer, faster, cheaper, halves, follows, best, ...) and refers
//!   to measured data (a figure marker, a variant's name in backticks, a
//!   table or plot, a measured field) without a claim. A comparative
//!   sentence that is not about a measurement says so, and why:
//!   `<!-- no claim: geometry, not a measurement -->`. Not scanned: code
//!   blocks, includes, tables, headings, HTML blocks (figures), link texts
//!   (section titles), and a test's or an exercise's criterion that quotes
//!   no figure (`Criterion: ...`, an exercise's `The goal: ...` or
//!   `Hint: ...`, a sentence naming a `lesson_NN_...` test): the test it
//!   names is its check.
//!
//! Pure std and the generator's own modules; no GPU. The scanner is tested
//! on in-memory text first.

use common::measure::counters::TEXELS_READ;
use generator::claims;
use generator::prose;
use generator::record;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use prose::Measured;
use record::Stat;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The chapters whose comparative sentences must carry claims.
const CHECKED: &[&str] = &[
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
    "using.md",
    "lesson_01_records.md",
    "lesson_02_records.md",
    "lesson_03_records.md",
    "lesson_04_records.md",
    "lesson_05_records.md",
    "lesson_06_records.md",
    "lesson_07_records.md",
    "lesson_08_records.md",
    "lesson_09_records.md",
    "lesson_10_records.md",
    "choosing_records.md",
];

/// Words (lower case, whole words or phrases) that make a sentence compare.
const COMPARATIVE: &[&str] = &[
    "more",
    "less",
    "fewer",
    "faster",
    "slower",
    "cheaper",
    "costlier",
    "dearer",
    "halves",
    "halved",
    "doubles",
    "doubled",
    "removes most",
    "most of",
    "follows",
    "tight",
    "tighter",
    "beats",
    "wins",
    "worst",
    "best",
    "most accurate",
    "least",
    "larger",
    "largest",
    "smaller",
    "smallest",
    "higher",
    "highest",
    "lower",
    "lowest",
    "better",
    "worse",
    "than",
    "twice",
    "no measurable",
    "falls",
    "grows",
    "rises",
    "cheapest",
    "fastest",
    "slowest",
    "shrinks",
    "saves",
    "exceeds",
    "times as",
    "as much",
];

/// Plain words that name measured data.
const MEASURED_WORDS: &[&str] = &[
    "table",
    "tables",
    "plot",
    "plots",
    "column",
    "misclassified",
    "misclassifies",
    "misclassify",
    "bleeding",
    "false shadow",
    "false-shadow",
    "false-lit",
    "mean |δv|",
];

/// What a sentence's comparison is checked against: the variants' names
/// and the fields (counters, passes) of every committed record.
struct Vocabulary {
    names: BTreeSet<String>,
}

fn vocabulary() -> Vocabulary {
    let mut names: BTreeSet<String> = [
        "misclassified_pct",
        "false_shadow_pct",
        "false_lit_pct",
        "mean_abs",
        "penumbra_mean_abs",
        "light_bleeding_pct",
        "umbra_misclassified_pct",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let mut stack = vec![root().join("book/src/generated")];
    while let Some(d) = stack.pop() {
        for e in fs::read_dir(&d).expect("generated").flatten() {
            let p = e.path();
            if p.is_dir() {
                if !p.ends_with("sets") {
                    stack.push(p);
                }
                continue;
            }
            if p.extension().is_none_or(|x| x != "json") {
                continue;
            }
            let Ok(v) =
                serde_json::from_str::<serde_json::Value>(&fs::read_to_string(&p).expect("record"))
            else {
                continue;
            };
            for variant in v["variants"].as_array().into_iter().flatten() {
                if let Some(n) = variant["name"].as_str() {
                    names.insert(n.to_string());
                }
                if let Some(c) = variant["counters"].as_object() {
                    names.extend(c.keys().cloned());
                }
                if let Some(c) = variant["timing"]["passes"].as_object() {
                    names.extend(c.keys().cloned());
                }
            }
        }
    }
    Vocabulary { names }
}

/// A sentence of prose: where it starts and its text (comments included).
#[derive(Debug)]
struct Sentence {
    line: usize,
    text: String,
}

/// The sentences of `markdown`'s prose: paragraphs and list items, not code
/// blocks, includes, tables or headings.
fn sentences(markdown: &str) -> Vec<Sentence> {
    // Paragraphs as (first line, text joined with spaces, line of each char).
    let mut blocks: Vec<Vec<(usize, char)>> = Vec::new();
    let mut current: Vec<(usize, char)> = Vec::new();
    let mut fenced = false;
    let mut in_comment = false;
    let flush = |current: &mut Vec<(usize, char)>, blocks: &mut Vec<Vec<(usize, char)>>| {
        if !current.is_empty() {
            blocks.push(std::mem::take(current));
        }
    };
    let mut view = false;
    for (n, line) in markdown.lines().enumerate() {
        let t = line.trim();
        if !in_comment && (t.starts_with("```") || t.starts_with("~~~")) {
            fenced = !fenced;
            flush(&mut current, &mut blocks);
            continue;
        }
        if fenced {
            continue;
        }
        // A view of a generated table (book/generate/views.rs): the
        // generator's header, table and legend, not the chapter's sentences.
        if t.starts_with("<!--view:") {
            view = true;
        }
        if view {
            view = !t.contains("<!--/view-->");
            flush(&mut current, &mut blocks);
            continue;
        }
        // HTML blocks (figures and their captions) are not sentences here.
        let html = t.starts_with('<') && !t.starts_with("<!--");
        let structural = t.is_empty()
            || html
            || t.starts_with("{{#")
            || (t.starts_with('|') && t.ends_with('|'))
            || t.starts_with('#')
            || t.starts_with("$$");
        if !in_comment && structural {
            flush(&mut current, &mut blocks);
            continue;
        }
        let item = t.starts_with("- ")
            || t.starts_with("* ")
            || t.split_once(". ")
                .is_some_and(|(a, _)| !a.is_empty() && a.chars().all(|c| c.is_ascii_digit()));
        if !in_comment && item {
            flush(&mut current, &mut blocks);
        }
        if !current.is_empty() {
            current.push((n + 1, ' '));
        }
        current.extend(t.chars().map(|c| (n + 1, c)));
        // Track comments spanning lines, so a claim may wrap.
        let mut rest = t;
        loop {
            if in_comment {
                match rest.find("-->") {
                    Some(e) => {
                        in_comment = false;
                        rest = &rest[e + 3..];
                    }
                    None => break,
                }
            } else {
                match rest.find("<!--") {
                    Some(s) => {
                        in_comment = true;
                        rest = &rest[s + 4..];
                    }
                    None => break,
                }
            }
        }
    }
    flush(&mut current, &mut blocks);
    let mut out = Vec::new();
    for block in blocks {
        let chars: Vec<char> = block.iter().map(|&(_, c)| c).collect();
        let mut start = 0;
        let mut i = 0;
        let mut code = false;
        while i < chars.len() {
            if chars[i..].starts_with(&['<', '!', '-', '-']) {
                // Skip the comment whole.
                let s: String = chars[i..].iter().collect();
                i += s
                    .find("-->")
                    .map_or(chars.len() - i, |e| s[..e + 3].chars().count());
                continue;
            }
            if chars[i] == '`' {
                code = !code;
            }
            let abbreviation = chars[i] == '.' && {
                let before: String = chars[start..i].iter().collect();
                let word = before
                    .rsplit(|c: char| c.is_whitespace() || c == '(')
                    .next();
                word.is_some_and(|w| ["e.g", "i.e", "cf", "vs", "Fig", "approx"].contains(&w))
            };
            let ends = !code
                && !abbreviation
                && matches!(chars[i], '.' | '?' | '!')
                && chars.get(i + 1).is_some_and(|c| c.is_whitespace())
                && chars
                    .get(i + 2)
                    .is_some_and(|c| c.is_uppercase() || matches!(c, '`' | '*' | '[' | '<'));
            i += 1;
            if ends {
                // A comment right after the full stop belongs to the sentence.
                let mut j = i;
                while j < chars.len() && chars[j].is_whitespace() {
                    j += 1;
                }
                if chars[j..].starts_with(&['<', '!', '-', '-']) {
                    let s: String = chars[j..].iter().collect();
                    if !s.starts_with(prose::OPEN) {
                        j += s
                            .find("-->")
                            .map_or(chars.len() - j, |e| s[..e + 3].chars().count());
                        i = j;
                    }
                }
                out.push(Sentence {
                    line: block[start].0,
                    text: chars[start..i]
                        .iter()
                        .collect::<String>()
                        .trim()
                        .to_string(),
                });
                start = i;
            }
        }
        if start < chars.len() {
            let text = chars[start..].iter().collect::<String>().trim().to_string();
            if !text.is_empty() {
                out.push(Sentence {
                    line: block[start].0,
                    text,
                });
            }
        }
    }
    out
}

/// `text` without comments, filled markers and inline code.
fn prose_only(text: &str) -> String {
    let mut s = text.to_string();
    while let Some(a) = s.find(prose::OPEN) {
        match s[a..].find(prose::CLOSE) {
            Some(b) => s.replace_range(a..a + b + prose::CLOSE.len(), " "),
            None => break,
        }
    }
    for (open, close) in [("<!--", "-->"), ("`", "`")] {
        while let Some(a) = s.find(open) {
            match s[a + open.len()..].find(close) {
                Some(b) => s.replace_range(a..a + open.len() + b + close.len(), " "),
                None => break,
            }
        }
    }
    // A link's text names a section or a page: a title, not a comparison.
    while let Some(m) = s.find("](") {
        let (Some(a), Some(b)) = (s[..m].rfind('['), s[m..].find(')')) else {
            break;
        };
        s.replace_range(a..m + b + 1, " ");
    }
    s
}

/// Whether `phrase` occurs in `text` as whole words.
fn has_words(text: &str, phrase: &str) -> bool {
    let lower = text.to_lowercase();
    let word = |c: char| c.is_alphanumeric() || c == '_' || c == '-';
    lower.match_indices(phrase).any(|(at, _)| {
        lower[..at].chars().next_back().is_none_or(|c| !word(c))
            && lower[at + phrase.len()..]
                .chars()
                .next()
                .is_none_or(|c| !word(c))
    })
}

/// The first comparative word of the sentence, if any.
fn comparative(text: &str) -> Option<&'static str> {
    let p = prose_only(text);
    COMPARATIVE.iter().copied().find(|w| has_words(&p, w))
}

/// What measured data the sentence refers to, if any.
fn measured(text: &str, vocabulary: &Vocabulary) -> Option<String> {
    if text.contains(prose::OPEN) {
        return Some("a figure marker".into());
    }
    let mut rest = text;
    while let Some(a) = rest.find('`') {
        let Some(b) = rest[a + 1..].find('`') else {
            break;
        };
        let code = &rest[a + 1..a + 1 + b];
        if vocabulary.names.contains(code) {
            return Some(format!("`{code}`"));
        }
        rest = &rest[a + 2 + b..];
    }
    let p = prose_only(text);
    if let Some(w) = MEASURED_WORDS.iter().find(|w| has_words(&p, w)) {
        return Some(w.to_string());
    }
    // A field's or counter's own name, written plain: `texels_read`.
    vocabulary
        .names
        .iter()
        .find(|n| n.contains('_') && has_words(&p, n))
        .cloned()
}

/// Whether the sentence states a test's or an exercise's pass criterion
/// (`Criterion: ...`, `The goal: ...`, or a named test's assertion) and
/// quotes no measured figure: the test it names is its check.
fn criterion(text: &str) -> bool {
    if text.contains(prose::OPEN) {
        return false;
    }
    let plain = prose_only(text);
    let plain = plain.trim_start_matches(['-', ' ']);
    if ["Criterion:", "The goal:", "Hint:"]
        .iter()
        .any(|p| plain.starts_with(p))
    {
        return true;
    }
    text.split('`').skip(1).step_by(2).any(|code| {
        code.starts_with("lesson_")
            && code.matches('_').count() >= 3
            && code.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    })
}

/// `(line, why, sentence)` for every comparative sentence about measured
/// data that carries neither a claim nor a `no claim` note.
fn unclaimed(markdown: &str, vocabulary: &Vocabulary) -> Vec<(usize, String, String)> {
    let mut out = Vec::new();
    for s in sentences(markdown) {
        if s.text.contains(claims::OPEN) || s.text.contains("<!-- no claim:") || criterion(&s.text)
        {
            continue;
        }
        let Some(word) = comparative(&s.text) else {
            continue;
        };
        let Some(data) = measured(&s.text, vocabulary) else {
            continue;
        };
        out.push((s.line, format!("\"{word}\" about {data}"), s.text));
    }
    out
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

/// A fake record lookup for the evaluator's tests.
fn fake(key: &str) -> anyhow::Result<Measured> {
    let t = |median, q25, q75| Measured::Time(Stat { median, q25, q75 });
    Ok(match key {
        "r:a:pct" => Measured::Pct(9.049),
        "r:b:pct" => Measured::Pct(4.995),
        "r:a:n" => Measured::Count(64),
        "r:b:n" => Measured::Count(64),
        "r:a:t" => t(23.5, 23.0, 24.0),
        "r:b:t" => t(31.2, 30.5, 32.0),
        "r:c:t" => t(27.1, 23.8, 28.0),
        _ => anyhow::bail!("no key {key}"),
    })
}

#[test]
fn claims_are_evaluated_on_numbers_and_spreads() {
    let holds = |c: &str| claims::eval(c, &mut fake).expect(c).holds;
    assert!(holds("r:a:pct > r:b:pct"));
    assert!(!holds("r:a:pct > 2 * r:b:pct"));
    assert!(holds("r:a:pct > 1.5 * r:b:pct"));
    assert!(holds("r:a:pct < 10"));
    assert!(holds("r:a:n == r:b:n; r:a:n >= 64"));
    assert!(!holds("r:a:n == r:b:n; r:a:n > 64"));
    assert!(holds("r:a:t faster r:b:t"));
    assert!(!holds("r:b:t faster r:a:t"));
    assert!(holds("r:b:t slower r:a:t"));
    assert!(holds("r:a:t apart r:b:t"));
    assert!(holds("r:a:t overlap r:c:t"));
    assert!(!holds("r:a:t apart r:c:t"));
    let shown = claims::eval("r:a:pct > 2 * r:b:pct", &mut fake).expect("evaluates");
    assert_eq!(shown.shown, "9.049 > 2 × 4.995 = 9.99");
    // A false claim shows only its false comparisons.
    let shown = claims::eval("r:a:pct > r:b:pct; r:a:n > 64", &mut fake).expect("evaluates");
    assert_eq!((shown.holds, shown.shown.as_str()), (false, "64 > 64"));
    // Malformed claims are errors, not verdicts.
    for bad in [
        "r:a:pct",
        "r:a:pct > ",
        "r:a:pct faster r:b:t",
        "r:a:pct > r:zz:pct",
        "r:a:pct > x",
        "r:a:t < r:b:t > r:c:t",
    ] {
        assert!(claims::eval(bad, &mut fake).is_err(), "{bad}");
    }
    // Claims are found outside code, also when they wrap.
    let text = "a <!--claim: r:a:pct > r:b:pct--> b\n```\n<!--claim: x-->\n```\nc <!--claim: r:a:t\n  faster r:b:t-->.\n";
    assert_eq!(
        claims::claims(text),
        vec![
            (1, "r:a:pct > r:b:pct".to_string()),
            (5, "r:a:t faster r:b:t".to_string())
        ]
    );
}

#[test]
fn the_scanner_finds_unclaimed_comparisons() {
    let vocabulary = Vocabulary {
        names: ["vsm", TEXELS_READ.name]
            .iter()
            .map(|s| s.to_string())
            .collect(),
    };
    let text = "\
# A heading with `vsm` is faster

The `vsm` pass is faster than the other. It has a name.
A second line, with more texels_read.

`vsm` bleeds more<!--claim: r:a:pct > r:b:pct-->. The table shows fewer
pixels. <!-- no claim: geometry, not a measurement --> Then the
`vsm` is\nlarger than it was.

```text
`vsm` is faster than everything.
```
{{#include generated/lesson_10/results.md}}
| `vsm` | faster |

- `vsm`: better than the rest.
- A list item, about nothing measured, is better.

Tight means `round` is better: e.g. `vsm`. Done.

Criterion: `vsm` bleeds less than 1 %. `lesson_10_vsm_bleeds` asserts `vsm` is worse.
Hint: your `vsm` gets better as the margin grows.
<figure><figcaption>`vsm` is faster.</figcaption></figure>
The least-squares fit of `vsm`.
See [why `vsm` needs more](#why) for `vsm`.
";
    let found: Vec<(usize, String)> = unclaimed(text, &vocabulary)
        .into_iter()
        .map(|(l, why, _)| (l, why))
        .collect();
    assert_eq!(
        found,
        vec![
            (3, "\"faster\" about `vsm`".to_string()),
            (4, "\"more\" about texels_read".to_string()),
            (7, "\"larger\" about `vsm`".to_string()),
            (17, "\"better\" about `vsm`".to_string()),
            (20, "\"tight\" about `vsm`".to_string()),
        ],
        "{:#?}",
        unclaimed(text, &vocabulary)
    );
    // A sentence starts where its first word is.
    let s = sentences("One `vsm` here. Two more texels_read\nthere.");
    assert_eq!(s.len(), 2);
    assert_eq!(s[1].line, 1);
}

#[test]
fn every_claim_holds_on_the_committed_records() {
    let errors =
        claims::false_claims(&root(), &root().join("book/src/generated")).expect("chapters");
    assert!(
        errors.is_empty(),
        "claims the committed records contradict ({}): rewrite the sentence to what the \
         records show, and its claim with it:\n  {}",
        errors.len(),
        errors.join("\n  ")
    );
}

#[test]
fn every_comparison_of_measured_figures_carries_a_claim() {
    let vocabulary = vocabulary();
    let mut errors = Vec::new();
    for name in CHECKED {
        let path = root().join("book/src").join(name);
        let text = fs::read_to_string(&path).expect("chapter");
        for (line, why, sentence) in unclaimed(&text, &vocabulary) {
            errors.push(format!("{}:{line}: {why}: {sentence}", rel(&path)));
        }
    }
    assert!(
        errors.is_empty(),
        "sentences comparing measured figures without a claim ({}): add \
         `<!--claim: LEFT OP RIGHT-->` (book/generate/claims.rs) to each, or, for a \
         comparison that is not about a measurement, `<!-- no claim: WHY -->`:\n  {}",
        errors.len(),
        errors.join("\n  ")
    );
}

/// The comments a sentence holds (`<!--claim: …-->`, `<!-- no claim: …-->`,
/// markers) open and close on one line: mdBook parses a comment inside a
/// paragraph line by line, and one that runs on past its line is left
/// open ("Saw EOF in state Comment"), swallowing the text after it.
fn comments_left_open(markdown: &str) -> Vec<usize> {
    let mut open = Vec::new();
    let mut fenced = false;
    for (n, line) in markdown.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        // The last comment opened on the line is still open at its end.
        let unclosed = line
            .rfind("<!--")
            .is_some_and(|at| !line[at..].contains("-->"));
        if !fenced && unclosed {
            open.push(n + 1);
        }
    }
    open
}

#[test]
fn every_comment_in_a_sentence_closes_on_its_line() {
    assert_eq!(
        comments_left_open("a <!--claim: x < y;\ny > z--> b\n"),
        vec![1]
    );
    assert!(comments_left_open("the line that starts with `-->`\n").is_empty());
    assert!(comments_left_open("a <!--claim: x < y; y > z--> b\n").is_empty());
    let mut errors = Vec::new();
    for path in prose::chapters(&root().join("book/src")).expect("book/src") {
        let text = fs::read_to_string(&path).expect("chapter");
        for line in comments_left_open(&text) {
            errors.push(format!("{}:{line}", rel(&path)));
        }
    }
    assert!(
        errors.is_empty(),
        "comments that do not close on the line they open on (mdBook leaves them open and \
         swallows what follows): put each on one line:\n  {}",
        errors.join("\n  ")
    );
}

/// The lines (1-based) of `text` that start with a marker (`<!--fig:`,
/// `<!--claim:`) inside a paragraph: CommonMark reads such a line as a raw
/// HTML block, which breaks the paragraph there and prints the rest of the
/// line unrendered (`hard_pcf`'s64, code spans left as backticks).
fn markers_opening_a_line(text: &str) -> Vec<usize> {
    let lines: Vec<&str> = text.lines().collect();
    let mut fence = false;
    let mut out = Vec::new();
    for (i, l) in lines.iter().enumerate() {
        if l.trim_start().starts_with("```") {
            fence = !fence;
        }
        let marker =
            l.trim_start().starts_with("<!--fig:") || l.trim_start().starts_with("<!--claim:");
        if !fence && marker && i > 0 && !lines[i - 1].trim().is_empty() {
            out.push(i + 1);
        }
    }
    out
}

#[test]
fn no_marker_opens_a_line_of_a_paragraph() {
    assert_eq!(
        markers_opening_a_line("at 256² and\n  <!--fig:a:b:c-->2<!--/fig--> at 4096²\n"),
        vec![2]
    );
    assert!(markers_opening_a_line("at 256² and <!--fig:a:b:c-->2<!--/fig-->\n").is_empty());
    let mut errors = Vec::new();
    for path in prose::chapters(&root().join("book/src")).expect("book/src") {
        let text = fs::read_to_string(&path).expect("chapter");
        for line in markers_opening_a_line(&text) {
            errors.push(format!("{}:{line}", rel(&path)));
        }
    }
    assert!(
        errors.is_empty(),
        "lines that open with a marker inside a paragraph (mdBook prints them as raw HTML, \
         breaking the paragraph): join each to the line before:\n  {}",
        errors.join("\n  ")
    );
}
