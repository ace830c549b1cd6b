//! The chapters' "where each port departs" tables are the tables the ports'
//! cards make (`book/generate/ports.rs`): a card edited without
//! regenerating the book fails here.

use generator::ports;

#[test]
fn committed_port_tables_are_the_cards_tables() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (lesson, cards) in ports::lessons() {
        let path = root.join(format!("book/src/generated/{}/{lesson}.md", ports::DIR));
        let committed =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(
            committed,
            ports::table(cards),
            "{lesson}'s port table differs from its cards: run `cargo run --release --bin workbook -- book`"
        );
        for c in cards {
            assert!(committed.contains(&format!("`{}`", c.variant)));
        }
    }
}

/// The bibliography's list of the ports' files and commits is the cards'
/// (`generated/ports/sources.md`), and the bibliography includes it and
/// has an entry for every repository a card names.
#[test]
fn the_bibliography_cites_every_card_at_its_commit() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join(format!("book/src/generated/{}/sources.md", ports::DIR));
    let committed =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        committed,
        ports::sources(),
        "the ports' sources differ from their cards: run `cargo run --release --bin workbook -- book`"
    );
    let bib = std::fs::read_to_string(root.join("book/src/appendix/bibliography.md")).unwrap();
    assert!(bib.contains("{{#include ../generated/ports/sources.md}}"));
    for (_, cards) in ports::lessons() {
        for c in cards {
            for s in c.sources {
                assert!(
                    committed.contains(&format!("`{}`", s.commit)),
                    "{}: {}",
                    c.variant,
                    s.file
                );
            }
            assert!(
                bib.contains(&format!("https://github.com/{}>", c.repository)),
                "the bibliography has no entry for {} (`{}`)",
                c.repository,
                c.variant
            );
        }
    }
}
