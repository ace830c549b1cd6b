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
        "the lesson's variant that ports a renderer's default or one of its options (its `--variant` name; the sources table below says which)",
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
    ("variant", "the lesson's variant that ports a renderer's default or one of its options"),
    ("default or option", "`default` where the renderer runs it unless told otherwise (a tutorial's own listing counts as one); `option:` and the setting that turns it on, where a user must"),
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

/// The bibliography's list of every file a port was read from: one row per
/// repository, file and full commit, with the lessons' variants that read
/// it. Made from the cards, so a citation cannot drift from them.
pub fn sources() -> String {
    use std::collections::BTreeMap;
    let mut rows: BTreeMap<(&str, &str, &str), Vec<String>> = BTreeMap::new();
    for (lesson, cards) in lessons() {
        for c in cards {
            for s in c.sources {
                rows.entry((s.repository.unwrap_or(c.repository), s.file, s.commit))
                    .or_default()
                    .push(format!("{lesson} `{}`", c.variant));
            }
        }
    }
    let mut out =
        String::from("| repository | file | commit | read by |\n| --- | --- | --- | --- |\n");
    for ((repo, file, commit), readers) in rows {
        out += &format!(
            "| [{repo}](https://github.com/{repo}) | [`{file}`](https://github.com/{repo}/blob/{commit}/{file}) | `{commit}` | {} |\n",
            readers.join(", ")
        );
    }
    out + &legend(&[
        ("repository", "the renderer's public repository"),
        (
            "file",
            "a file a port's card was read from, linked at its commit",
        ),
        ("commit", "the full commit the file was read at"),
        (
            "read by",
            "the lessons' variants whose cards cite the file at that commit",
        ),
    ])
}

/// Writes every lesson's table under `generated/ports/`, and the
/// bibliography's list of sources (`sources.md`).
pub fn write_all(generated: &Path) -> Result<()> {
    let dir = generated.join(DIR);
    std::fs::create_dir_all(&dir)?;
    for (lesson, cards) in lessons() {
        std::fs::write(dir.join(format!("{lesson}.md")), table(cards))?;
    }
    std::fs::write(dir.join("sources.md"), sources())?;
    Ok(())
}
