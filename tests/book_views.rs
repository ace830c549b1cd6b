//! A chapter's tables are views of the generated tables its record page
//! shows in full (`<!--view: ...-->`, `book/generate/views.rs`). Fails,
//! naming the page and the line, when a view's table is not what its
//! source table makes today (a cell edited by hand, a source regenerated
//! without `workbook fill`), or names a row, a column or a source that
//! does not exist. The sources themselves are checked against their
//! records by `tests/generated.rs`, so a view is as checked as its source.
//!
//! Pure std and the generator's own module; no GPU.

use generator::prose;
use generator::views;

use std::fs;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

const FILL: &str = "fill it with `cargo run --release --bin workbook -- fill PAGE`";

#[test]
fn every_view_is_what_its_source_makes() {
    let src = root().join("book/src");
    let generated = src.join("generated");
    let mut failures = Vec::new();
    let mut count = 0;
    for page in prose::chapters(&src).expect("book/src") {
        let text = fs::read_to_string(&page).expect("a page");
        let name = page
            .strip_prefix(root())
            .unwrap_or(&page)
            .display()
            .to_string();
        match views::fill(&text, &mut |s| views::read_generated(&generated, s)) {
            Ok(filled) if filled == text => {}
            Ok(filled) => {
                let line = text
                    .lines()
                    .zip(filled.lines())
                    .position(|(a, b)| a != b)
                    .map_or(0, |i| i + 1);
                failures.push(format!(
                    "{name}:{line}: a view is not what its source makes ({FILL})"
                ));
            }
            Err(e) => failures.push(format!("{name}: {e:#}")),
        }
        count += views::views(&text).map_or(0, |v| v.len());
    }
    assert!(
        count > 0,
        "no page has a view: the check found nothing to check"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn an_edited_view_cell_is_caught() {
    // Take the first view of the book, change one cell of its table, and
    // check that filling it again restores the source's value.
    let src = root().join("book/src");
    let generated = src.join("generated");
    for page in prose::chapters(&src).expect("book/src") {
        let text = fs::read_to_string(&page).expect("a page");
        let Some((_, _, body)) = views::views(&text).expect("views parse").into_iter().next()
        else {
            continue;
        };
        let Some(row) = body.lines().filter(|l| l.starts_with('|')).nth(2) else {
            continue;
        };
        let edited_row = format!("{row} edited |");
        let edited = text.replacen(row, &edited_row, 1);
        let filled = views::fill(&edited, &mut |s| views::read_generated(&generated, s))
            .expect("the view fills");
        assert_ne!(filled, edited, "an edited cell went unnoticed");
        assert_eq!(filled, text, "filling did not restore the source's table");
        return;
    }
    panic!("no view in the book to edit");
}
