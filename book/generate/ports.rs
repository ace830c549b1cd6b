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
    vec![("lesson_10", workbook::lesson_10::port_cards::CARDS)]
}

/// A cell: no line breaks, no table pipes.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The table of `cards`: per port, its renderer, the files it was read
/// from (file at commit), and each departure with why.
pub fn table(cards: &[PortCard]) -> String {
    let mut out = String::from(
        "*made from the ports' cards (`port_cards.rs`); each card also lists every constant it takes, with its lines*\n\n",
    );
    out += "| variant | renderer | read from | what the port cannot do here | why |\n";
    out += "| --- | --- | --- | --- | --- |\n";
    for c in cards {
        let sources: Vec<String> = (c.sources.iter())
            .map(|s| format!("`{}` at `{}`", s.file, &s.commit[..7]))
            .collect();
        let sources = format!("{}: {}", c.repository, sources.join(", "));
        for (i, d) in c.departures.iter().enumerate() {
            let (variant, renderer, read) = match i {
                0 => (format!("`{}`", c.variant), c.renderer.to_string(), sources.clone()),
                _ => (String::new(), String::new(), String::new()),
            };
            out += &format!(
                "| {variant} | {renderer} | {} | {} | {} |\n",
                cell(&read),
                cell(d.what),
                cell(d.why)
            );
        }
    }
    out
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
