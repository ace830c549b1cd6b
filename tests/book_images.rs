//! The book's pictures on its white page (`book/generate/figures.rs`):
//!
//! - no image under `book/src/figures/` has a transparent pixel (on the
//!   white page, "no geometry" would read as lit);
//! - every error figure of `book/src/generated/figures.json` whose errors
//!   are sparse (under `SPARSE_PCT` % of its covered pixels: a few pixels
//!   that do not show at page size) gives its count of error pixels in its
//!   caption, and every diff or ΔV figure a chapter shows has its count;
//! - a diff whose errors are not sparse but one class of them is (a few
//!   green pixels among many red: `figures::Count::marked`) gives that
//!   class's count in its caption, since the figure draws them as dots;
//! - a diff marks the pixels of each sparse class, and only those.
//!
//! The ignored test `prepare_committed_figures` is the one-off that made
//! the committed figures from the raw copies the lessons wrote (`git show
//! 49310ab:<figure>`, the last commit before the step existed; a newer
//! figure from its run, `target/book-runs/<run>/r0/<file>`):
//!
//! ```text
//! cargo test --release --features solutions --test book_images -- --ignored prepare_committed_figures
//! ```
//!
//! It reads that commit's raw figures, never HEAD's prepared ones, so it
//! writes the same files however often it runs. `BOOK_FIGURES` (paths
//! under `figures/`, comma-separated) limits it to those figures, for
//! remaking a few after a change to the preparation step:
//!
//! ```text
//! BOOK_FIGURES=lesson_01/res_256_diff_l0.png,lesson_01/res_4096_diff_l0.png \
//!   cargo test --release --features solutions,chapter_copies --test book_images -- --ignored prepare_committed_figures
//! ```

use generator::figures;
use generator::manifest;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every PNG below `dir`, sorted.
fn pngs(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "png") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The figure's path under `book/src/figures/`, with `/`.
fn dest_of(path: &Path) -> String {
    let figures = root().join("book/src/figures");
    let rel = path.strip_prefix(&figures).unwrap_or(path);
    rel.to_string_lossy().replace('\\', "/")
}

/// The transparent pixels of each PNG: `(figure, count)` where not none.
fn transparent(paths: &[PathBuf]) -> Vec<(String, usize)> {
    paths
        .iter()
        .filter_map(|p| {
            let img = image::open(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            if !img.color().has_alpha() {
                return None;
            }
            let n = img.to_rgba8().pixels().filter(|c| c.0[3] < 255).count();
            (n > 0).then(|| (dest_of(p), n))
        })
        .collect()
}

#[test]
fn no_book_image_has_a_transparent_pixel() {
    let all = pngs(&root().join("book/src/figures"));
    assert!(all.len() > 40, "only {} book images found", all.len());
    let bad = transparent(&all);
    let list: Vec<String> = bad
        .iter()
        .map(|(f, n)| format!("  {f}: {n} transparent pixels"))
        .collect();
    assert!(
        bad.is_empty(),
        "{} book images have transparent pixels, which read as lit on the white page \
         (run them through book/generate/figures.rs):\n{}",
        bad.len(),
        list.join("\n")
    );
}

/// The integers a text gives, digit groups joined across a space, a
/// no-break or thin space, or a comma (`134 345`, `1,234`), each with the
/// text that follows it.
fn integers(text: &str) -> Vec<(u64, String)> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let chars: Vec<char> = text.chars().collect();
    let after = |i: usize| {
        chars[i.min(chars.len())..]
            .iter()
            .take(48)
            .collect::<String>()
    };
    for (i, &c) in chars.iter().enumerate() {
        if c.is_ascii_digit() {
            cur.push(c);
            continue;
        }
        let sep = matches!(c, ' ' | '\u{a0}' | '\u{202f}' | '\u{2009}' | ',');
        let next3 = chars.get(i + 1..i + 4).is_some_and(|n| {
            n.iter().all(char::is_ascii_digit)
                && !chars.get(i + 4).is_some_and(char::is_ascii_digit)
        });
        if sep && !cur.is_empty() && next3 {
            continue;
        }
        if let Ok(n) = cur.parse() {
            out.push((n, after(i)));
        }
        cur.clear();
    }
    if let Ok(n) = cur.parse() {
        out.push((n, String::new()));
    }
    out
}

/// Whether `caption` gives `count` as a number of pixels: the number,
/// then "pixel" within the next few words (`78 error pixels`,
/// `587 and 557 error pixels`).
fn gives_count(caption: &str, count: u64) -> bool {
    integers(caption)
        .iter()
        .any(|(n, rest)| *n == count && rest.to_lowercase().contains("pixel"))
}

/// Every figure a chapter shows: its path under `figures/`, the chapter,
/// and the caption of the `<figure>` it is in.
fn shown_figures() -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    let src = root().join("book/src");
    let mut chapters: Vec<PathBuf> = std::fs::read_dir(&src)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    chapters.sort();
    for ch in chapters {
        let text = std::fs::read_to_string(&ch).unwrap();
        let name = ch.file_name().unwrap().to_string_lossy().to_string();
        let mut rest = text.as_str();
        while let Some(at) = rest.find("src=\"figures/") {
            let after = &rest[at + "src=\"figures/".len()..];
            let dest = after.split('"').next().unwrap_or("").to_string();
            let caption = after
                .find("<figcaption>")
                .and_then(|s| {
                    let c = &after[s..];
                    c.find("</figcaption>").map(|e| c[..e].to_string())
                })
                .unwrap_or_default();
            out.push((dest, name.clone(), caption));
            rest = after;
        }
    }
    out
}

fn load_counts() -> BTreeMap<String, figures::Count> {
    figures::load_counts(&root().join("book/src/generated")).unwrap()
}

#[test]
fn sparse_error_figures_give_their_count() {
    let counts = load_counts();
    let shown = shown_figures();
    let mut bad = Vec::new();
    for (dest, chapter, caption) in &shown {
        let name = dest.rsplit('/').next().unwrap_or(dest);
        let is_error = dest.ends_with(".png")
            && !dest.starts_with("window/")
            && (name.contains("_diff") || name.contains("_dv"));
        if !is_error {
            continue;
        }
        let Some(c) = counts.get(dest) else {
            bad.push(format!(
                "{chapter}: {dest} has no count in generated/figures.json"
            ));
            continue;
        };
        let sparse =
            (c.error_pixels as f64) < figures::SPARSE_PCT / 100.0 * c.covered_pixels as f64;
        if sparse != c.sparse {
            bad.push(format!(
                "{chapter}: {dest}: figures.json's `sparse` is stale"
            ));
        }
        if sparse && !gives_count(caption, c.error_pixels) {
            bad.push(format!(
                "{chapter}: {dest} has {} error pixels of {} covered (under {} %), and its \
                 caption does not say so: at page size the figure looks error-free",
                c.error_pixels,
                c.covered_pixels,
                figures::SPARSE_PCT
            ));
        }
        // One class sparse, the other not: the figure dots that class.
        let (shadow, lit) = c.marked();
        for (marked, n, class) in [
            (shadow, c.darker, "false shadow (red)"),
            (lit, c.lighter, "false lit (green)"),
        ] {
            if marked && !sparse && !gives_count(caption, n) {
                bad.push(format!(
                    "{chapter}: {dest} has {n} {class} pixels of {} covered (under {} %), \
                     drawn as dots, and its caption does not give their count",
                    c.covered_pixels,
                    figures::SPARSE_PCT
                ));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn counts_are_read_from_captions() {
    let n = |t: &str| integers(t).into_iter().map(|(n, _)| n).collect::<Vec<_>>();
    assert_eq!(n("78 of 134 345 pixels"), vec![78, 134_345]);
    assert_eq!(n("1,234 and 5"), vec![1234, 5]);
    assert_eq!(n("at 2 000\u{a0}px"), vec![2000]);
    assert!(gives_count("Figure 10.3: 139 error pixels", 139));
    assert!(gives_count("(587 and 557 error pixels)", 587));
    assert!(gives_count("1 error pixel", 1));
    // A figure's number is not a count of pixels.
    assert!(!gives_count("Figure 6.2: the errors are gone", 2));
    assert!(!gives_count("Figure 10.3: where pcss is wrong", 3));
}

/// A raw diff of `w`×`h`, every pixel covered: `red` false-shadow pixels
/// in the first rows, then one false-lit pixel at `green`, the rest agreeing.
fn raw_diff(w: u32, h: u32, red: u32, green: (u32, u32)) -> Vec<u8> {
    use common::reference::metrics::{FALSE_LIT, FALSE_SHADOW};
    let img = image::RgbaImage::from_fn(w, h, |x, y| {
        if (x, y) == green {
            FALSE_LIT
        } else if y * w + x < red {
            FALSE_SHADOW
        } else {
            image::Rgba([128, 128, 128, 255])
        }
    });
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

#[test]
fn a_sparse_class_is_marked_beside_a_dense_one() {
    use common::reference::metrics::FALSE_LIT;
    let (w, h) = (100, 100);
    let green = (50, 80);
    let green_dots = |png: &[u8]| {
        let img = image::load_from_memory(png).unwrap().to_rgb8();
        img.pixels()
            .filter(|p| p.0 == [FALSE_LIT.0[0], FALSE_LIT.0[1], FALSE_LIT.0[2]])
            .count()
    };
    // Half the pixels red, one green: the red is left as it is, the green dotted.
    let p = figures::prepare("t/x_diff.png", &raw_diff(w, h, w * h / 2, green)).unwrap();
    let c = p.count.unwrap();
    assert_eq!(
        (c.darker, c.lighter, c.sparse),
        (w as u64 * h as u64 / 2, 1, false)
    );
    assert_eq!(c.marked(), (false, true));
    let r = figures::MARK_RADIUS as usize;
    assert!(green_dots(&p.png) > r * r, "the green pixel is a dot");
    let img = image::load_from_memory(&p.png).unwrap().to_rgb8();
    let reds = img.pixels().filter(|q| q.0 == [255, 0, 0]).count();
    assert_eq!(reds as u32, w * h / 2, "the dense red is not dotted");
    // Few red and the green: the whole figure is sparse, both are dotted.
    let p = figures::prepare("t/x_diff.png", &raw_diff(w, h, 3, green)).unwrap();
    assert_eq!(p.count.as_ref().unwrap().marked(), (true, true));
    assert!(green_dots(&p.png) > r * r);
    // A ΔV figure marks nothing.
    let dv = figures::Count {
        kind: "dv".into(),
        ..p.count.unwrap()
    };
    assert_eq!(dv.marked(), (false, false));
}

/// The last commit whose book figures were the lessons' raw copies.
const RAW_COMMIT: &str = "49310ab";

/// The one-off that made the committed figures (see the module's docs):
/// each figure as [`RAW_COMMIT`] held it, raw, through
/// `figures::prepare`, so running it again writes the same files.
#[test]
#[ignore = "rewrites book/src/figures from the raw copies at RAW_COMMIT"]
fn prepare_committed_figures() {
    let figs = root().join("book/src/figures");
    let generated = root().join("book/src/generated");
    let mut counts = figures::load_counts(&generated).unwrap();
    // What RAW_COMMIT holds, or the run's own file for a newer figure.
    let from_runs: BTreeMap<&str, PathBuf> = manifest::FIGURES
        .iter()
        .map(|f| {
            let src = root()
                .join("target/book-runs")
                .join(f.run)
                .join("r0")
                .join(f.file);
            (f.dest, src)
        })
        .collect();
    let mut dests: Vec<String> = pngs(&figs).iter().map(|p| dest_of(p)).collect();
    dests.extend(
        from_runs
            .keys()
            .filter(|d| d.ends_with(".png"))
            .map(|d| d.to_string()),
    );
    dests.sort();
    dests.dedup();
    if let Ok(only) = std::env::var("BOOK_FIGURES") {
        let only: Vec<&str> = only.split(',').map(str::trim).collect();
        dests.retain(|d| only.contains(&d.as_str()));
        assert_eq!(
            dests.len(),
            only.len(),
            "BOOK_FIGURES names a figure it cannot find"
        );
    }
    for dest in dests {
        let head = std::process::Command::new("git")
            .args(["show", &format!("{RAW_COMMIT}:book/src/figures/{dest}")])
            .current_dir(root())
            .output()
            .unwrap();
        let raw = if head.status.success() {
            head.stdout
        } else if let Some(src) = from_runs.get(dest.as_str()).filter(|p| p.exists()) {
            std::fs::read(src).unwrap()
        } else {
            eprintln!("{dest}: neither in {RAW_COMMIT} nor in target/book-runs; left as it is");
            continue;
        };
        let p = figures::prepare(&dest, &raw).unwrap();
        let path = figs.join(&dest);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &p.png).unwrap();
        match p.count {
            Some(c) => counts.insert(dest.clone(), c),
            None => counts.remove(&dest),
        };
    }
    figures::write_counts(&generated, &counts).unwrap();
}
