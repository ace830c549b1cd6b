//! The chapters' "where each port departs" tables, made from the ports'
//! cards (`lessons/lesson_NN/port_cards.rs`, [`common::ports`]): one table
//! per lesson, `generated/ports/lesson_NN.md`, that lists each port's
//! sources at their commits and what it cannot do here.

use std::path::Path;

use anyhow::Result;
use common::ports::PortCard;

/// The folder under `generated/`.
pub const DIR: &str = "ports";

/// The lessons with ports, and their cards.
pub fn lessons() -> Vec<(&'static str, &'static [PortCard])> {
    vec![
        ("lesson_02", workbook::lesson_02::port_cards::CARDS),
        ("lesson_03", workbook::lesson_03::port_cards::CARDS),
        ("lesson_04", workbook::lesson_04::port_cards::CARDS),
        ("lesson_10", workbook::lesson_10::port_cards::CARDS),
    ]
}

/// The table of `cards` ([`common::ports::departures_table`]): each
/// departure with why, then each port's files at their commits.
pub fn table(cards: &[PortCard]) -> String {
    let text = common::ports::departures_table(cards);
    let (departures, sources) = text.split_once("\n\n").unwrap_or((&text, ""));
    let mut out = format!("{}\n{}", departures.trim_end(), legend(DEPARTURE_COLUMNS));
    if !sources.trim().is_empty() {
        out += &format!("\n{}\n{}", sources.trim_end(), legend(SOURCE_COLUMNS));
    }
    out
}

/// The departures table's columns.
const DEPARTURE_COLUMNS: &[(&str, &str)] = &[
    (
        "variant",
        "the lesson's variant that ports a renderer's default (its `--variant` name)",
    ),
    (
        "renderer",
        "the renderer or tutorial whose source the port follows",
    ),
    (
        "what the port cannot do here",
        "one thing the renderer's source does that the port does not, a row of the port's card",
    ),
    ("why", "the reason, and what the port does instead"),
];

/// The sources table's columns.
const SOURCE_COLUMNS: &[(&str, &str)] = &[
    ("variant", "the lesson's variant that ports a renderer's default"),
    ("repository", "the renderer's public repository, `owner/name`"),
    ("read at", "each file the port's card was read from, at its commit (the card gives the full commit and each constant's lines)"),
];

/// A legend under a table, in the book's form.
fn legend(columns: &[(&str, &str)]) -> String {
    let mut s = String::from("\n<details><summary>What each column means</summary>\n\n");
    for (c, d) in columns {
        s += &format!("- {c}: {d}\n");
    }
    s + "\n</details>\n"
}

/// Writes every lesson's table under `generated/ports/`.
pub fn write_all(generated: &Path) -> Result<()> {
    let dir = generated.join(DIR);
    std::fs::create_dir_all(&dir)?;
    for (lesson, cards) in lessons() {
        std::fs::write(dir.join(format!("{lesson}.md")), table(cards))?;
    }
    Ok(())
}
