//! The hand-written pages name their sources (never "seed"), and every
//! link between the book's pages lands on a page and, with a `#fragment`,
//! on one of its headings or ids.

use std::collections::{BTreeSet, HashMap};
use std::fs;
use std::path::{Path, PathBuf};

use crate::helpers::{fail_with, markdown_files, repo_root};
use crate::parse::{link_target, normalize, prose_lines, strip_fragment};

/// `(line, word)` of every word that starts with "seed", any case
/// (`seed`, `Seeds'`, `constant_seed`): the workbook names its sources
/// instead ("the lwjgl book", "tinyrenderer's shadow lesson").
fn seed_words(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let lower = line.to_ascii_lowercase();
        for (at, _) in lower.match_indices("seed") {
            let before = lower[..at].chars().next_back();
            if before.is_some_and(|c| c.is_ascii_alphabetic()) {
                continue; // "linseed" is not the word
            }
            let end = lower[at..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '\''))
                .map_or(line.len(), |e| at + e);
            found.push((n + 1, line[at..end].to_string()));
        }
    }
    found
}

/// The sources the workbook follows, as the bibliography must name them:
/// each entry is the words that must all appear, spelt as here. Proper
/// names are matched with their capitals, so that the bibliography's
/// lower-case keys (`[heidmann]`) do not count as naming the source.
const SOURCES: &[&[&str]] = &[
    &["ogldev", "Tutorial 40"],
    &["LWJGL", "Hernández Bejarano"],
    &["yyh", "DonewsBlog"],
    &["tinyrenderer", "Sokolov"],
    &["Pupius"],
    &["Everitt"],
    &["Kilgard"],
    &["Common Techniques to Improve Shadow Depth Maps"],
    &["Cascaded Shadow Maps"],
    &["Williams"],
    &["Crow"],
    &["Heidmann"],
];

/// The sources of [`SOURCES`] that `bibliography` does not name.
fn missing_sources(bibliography: &str) -> Vec<String> {
    SOURCES
        .iter()
        .filter(|words| !words.iter().all(|w| bibliography.contains(w)))
        .map(|words| words.join(" + "))
        .collect()
}

/// A heading's id as mdBook makes it: inline markup dropped, letters,
/// digits, `_` and `-` kept (ASCII lower-cased), each blank a `-`.
fn heading_id(heading: &str) -> String {
    heading
        .trim()
        .trim_start_matches('#')
        .trim()
        .chars()
        .filter(|c| !matches!(c, '`' | '*'))
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                Some(c.to_ascii_lowercase())
            } else if c.is_whitespace() {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// Every fragment a page answers to: its headings' ids (a repeated id
/// gets `-1`, `-2`, … as mdBook does) and every `id="…"` it writes.
fn page_ids(markdown: &str) -> BTreeSet<String> {
    let mut ids = BTreeSet::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut fence = false;
    for line in markdown.lines() {
        let t = line.trim_start();
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = !fence;
            continue;
        }
        if fence {
            continue;
        }
        if t.starts_with('#') {
            let id = heading_id(t);
            let n = seen.entry(id.clone()).or_insert(0);
            ids.insert(if *n == 0 { id } else { format!("{id}-{n}") });
            *n += 1;
        }
        let mut rest = line;
        while let Some(at) = rest.find("id=\"") {
            rest = &rest[at + 4..];
            if let Some(end) = rest.find('"') {
                ids.insert(rest[..end].to_string());
            }
        }
    }
    ids
}

/// `(line, target)` of every `[text](target)` link that stays in the
/// book: no scheme, not an image.
fn local_links(markdown: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (line, text) in prose_lines(markdown) {
        let mut rest = text.as_str();
        while let Some(at) = rest.find("](") {
            let image = rest[..at]
                .rfind('[')
                .is_some_and(|o| rest[..o].ends_with('!'));
            if let Some(target) = link_target(&rest[at + 2..]) {
                if !image && !target.contains("://") && !target.starts_with("mailto:") {
                    found.push((line, target));
                }
            }
            rest = &rest[at + 2..];
        }
    }
    found
}

/// Errors for `chapter`'s links (paths relative to the book's `src`)
/// whose page is missing or has no heading or id for the fragment.
fn check_links(pages: &HashMap<PathBuf, String>, chapter: &Path, markdown: &str) -> Vec<String> {
    let dir = chapter.parent().unwrap_or(Path::new(""));
    let mut errors = Vec::new();
    for (line, target) in local_links(markdown) {
        let path = strip_fragment(&target);
        let page = if path.is_empty() {
            chapter.to_path_buf()
        } else {
            normalize(&dir.join(path))
        };
        if !path.is_empty() && !path.ends_with(".md") {
            continue; // a file, not a page: the include check's job
        }
        let Some(text) = pages.get(&page) else {
            errors.push(format!(
                "{}:{line}: link to missing page {target}",
                chapter.display()
            ));
            continue;
        };
        if let Some((_, fragment)) = target.split_once('#') {
            if !page_ids(text).contains(fragment) {
                errors.push(format!(
                    "{}:{line}: {target}: no heading or id \"{fragment}\" in {}",
                    chapter.display(),
                    page.display()
                ));
            }
        }
    }
    errors
}

/// The hand-written pages: every `.md` under `book/src` but `generated/`.
fn written_pages(src: &Path) -> HashMap<PathBuf, String> {
    markdown_files(src)
        .into_iter()
        .filter(|p| !p.starts_with(src.join("generated")))
        .map(|p| {
            let text = fs::read_to_string(&p)
                .unwrap_or_else(|e| panic!("cannot read {}: {e}", p.display()));
            (p.strip_prefix(src).unwrap_or(&p).to_path_buf(), text)
        })
        .collect()
}

#[test]
fn checkers_find_seeds_sources_and_broken_fragments() {
    let seeds = seed_words("the Seeds' constant\n`constant_seed`, linseed, seeded\n");
    let words: Vec<&str> = seeds.iter().map(|(_, w)| w.as_str()).collect();
    assert_eq!(words, ["Seeds'", "seed", "seeded"], "{seeds:?}");
    assert_eq!(seeds[1].0, 2);
    assert!(seed_words("the lwjgl book's constant, proceed").is_empty());

    let all = "ogldev Tutorial 40, LWJGL by Hernández Bejarano, yyh on DonewsBlog, \
               tinyrenderer by Sokolov, Pupius, Everitt and Kilgard, Common \
               Techniques to Improve Shadow Depth Maps, Cascaded Shadow Maps, \
               Williams, Crow, Heidmann";
    assert!(
        missing_sources(all).is_empty(),
        "{:?}",
        missing_sources(all)
    );
    let without = all
        .replace("Heidmann", "[heidmann] H.")
        .replace("DonewsBlog", "a blog");
    assert_eq!(missing_sources(&without), ["yyh + DonewsBlog", "Heidmann"]);

    assert_eq!(
        heading_id("## Why acne appears: texel footprint × tan θ"),
        "why-acne-appears-texel-footprint--tan-θ"
    );
    assert_eq!(heading_id("## To infinity: w = 0"), "to-infinity-w--0");
    assert_eq!(
        heading_id("### The `pcf` kernel's *taps*"),
        "the-pcf-kernels-taps"
    );
    let page = "# Top\n## Results\n```\n# not a heading\n```\n## Results\n\
                <a id=\"lwjgl\"></a>**[lwjgl]** …\n";
    let ids = page_ids(page);
    let want = ["lwjgl", "results", "results-1", "top"];
    assert_eq!(ids.iter().map(String::as_str).collect::<Vec<_>>(), want);

    let pages: HashMap<PathBuf, String> = [
        (PathBuf::from("appendix/bibliography.md"), page.to_string()),
        (
            PathBuf::from("lesson_01.md"),
            "# 01\n## The light's view\n".into(),
        ),
    ]
    .into();
    let chapter = Path::new("appendix/glossary.md");
    let good = "[a](bibliography.md#lwjgl) [b](../lesson_01.md#the-lights-view) \
                ![img](../figures/x.png) [c](https://example.org#x)\n";
    assert_eq!(check_links(&pages, chapter, good), Vec::<String>::new());
    let bad = "[a](bibliography.md#gone)\n[b](../lesson_02.md)\n`[c](nowhere.md)`\n";
    let errors = check_links(&pages, chapter, bad);
    assert_eq!(errors.len(), 2, "{errors:#?}");
    assert!(errors[0].contains(":1:") && errors[0].contains("\"gone\""));
    assert!(errors[1].contains(":2:") && errors[1].contains("missing page"));
}

/// "Seed" meant nothing to a reader: the book names its sources. Only the
/// hand-written pages are checked. `book/src/generated/` is left out on
/// purpose: the generator rewrites it from the lessons' variant names, so
/// a stale `constant_seed` there is fixed by rerunning the generator
/// (`cargo run --release --bin workbook -- book`), not by editing it.
#[test]
fn the_book_names_its_sources_and_never_says_seed() {
    let root = repo_root();
    let src = root.join("book/src");
    let mut pages: Vec<(PathBuf, String)> = written_pages(&src)
        .into_iter()
        .map(|(p, text)| (Path::new("book/src").join(p), text))
        .collect();
    let readme = fs::read_to_string(root.join("README.md")).expect("README.md");
    pages.push((PathBuf::from("README.md"), readme));
    let mut errors = Vec::new();
    for (page, text) in &pages {
        for (line, word) in seed_words(text) {
            errors.push(format!(
                "{}:{line}: \"{word}\": name the source instead",
                page.display()
            ));
        }
    }
    let bibliography = fs::read_to_string(src.join("appendix/bibliography.md"))
        .expect("book/src/appendix/bibliography.md");
    for source in missing_sources(&bibliography) {
        errors.push(format!(
            "book/src/appendix/bibliography.md does not name {source}"
        ));
    }
    fail_with(&errors, "the book must name its sources");
}

/// Every link between the book's pages lands on a page that exists and,
/// with a `#fragment`, on one of its headings or `id`s (mdBook itself
/// builds a link to a missing heading without a word).
#[test]
fn links_between_pages_land_on_a_heading() {
    let src = repo_root().join("book/src");
    let pages = written_pages(&src);
    let mut errors = Vec::new();
    let mut links = 0;
    for (page, text) in &pages {
        links += local_links(text).len();
        errors.extend(check_links(&pages, page, text));
    }
    eprintln!("checked {links} links in {} pages", pages.len());
    assert!(links > 0, "no links found under {}", src.display());
    fail_with(&errors, "links between the book's pages");
}
