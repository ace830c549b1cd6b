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
    common::ports::departures_table(cards)
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
