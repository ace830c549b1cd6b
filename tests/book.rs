//! The book must not drift from the code. This test reads `book/src/` and
//! fails, with the file and line, when:
//!
//! - an `{{#include PATH}}`, `{{#include PATH:ANCHOR}}`, `{{#rustdoc_include ..}}`
//!   or `{{#playground ..}}` names a file that does not exist (PATH is
//!   relative to the chapter), or an ANCHOR that the file does not open with
//!   `ANCHOR: name` and close with `ANCHOR_END: name`;
//! - an image `![..](path)` or `<img src="..">` points to a missing file;
//! - `SUMMARY.md` links a missing file;
//! - a lesson, a `lessons/lesson_NN/` folder with a `main.rs`, has no
//!   `book/src/lesson_NN.md` listed in `SUMMARY.md`;
//! - a lesson chapter `lesson_NN.md` takes less than [`share::MIN_OWN_SHARE`] of
//!   its listing lines from its own lesson's files (`lessons/lesson_NN/`
//!   and `shaders/lesson_NN/`); listings from `common/` or from another
//!   lesson count as not its own, and included generated tables
//!   (`book/src/generated/`) are results, not listings. Run with `--nocapture` to see the table
//!   of every chapter's share;
//! - a lesson chapter's technique listing holds a harness name (the exercise
//!   switch, counters, timing, readbacks, the buffer view, the ports' model
//!   switches: [`listings`]);
//! - chapter 05 does not list `silhouette_edges`, or chapter 06 shows no
//!   code of `lessons/lesson_06/`.
//!
//! mdbook itself only logs a missing include and builds anyway, so without
//! this test a renamed anchor silently empties a listing.
//!
//! Pure std: no mdbook needed. The checker's parsers are tested on in-memory
//! text first, so a broken checker cannot pass by finding nothing.
//!
//! The checks, one module a concept (in `tests/book/`):
//! - [`parse`]: mdBook's directives, anchors, images and links, read as mdBook does.
//! - [`includes`]: includes and their anchors resolve, images exist.
//! - [`summary`]: SUMMARY.md's links exist, every lesson has a listed chapter.
//! - [`share`]: a lesson chapter shows mostly its own lesson's code.
//! - [`listings`]: a lesson chapter's listings hold the technique, not the harness.
//! - [`sources_and_links`]: pages name their sources, links land on a heading.
//! - [`helpers`]: the files the checkers read (disk or memory), the failure message.

#[path = "book/helpers.rs"]
mod helpers;
#[path = "book/includes.rs"]
mod includes;
#[path = "book/listings.rs"]
mod listings;
#[path = "book/parse.rs"]
mod parse;
#[path = "book/share.rs"]
mod share;
#[path = "book/sources_and_links.rs"]
mod sources_and_links;
#[path = "book/summary.rs"]
mod summary;
