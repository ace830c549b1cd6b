//! The chapters' "where each port departs" tables are the tables the ports'
//! cards make (`book/generate/ports.rs`): a card edited without
//! regenerating the book fails here.

#[path = "../book/generate/ports.rs"]
#[allow(dead_code)]
mod ports;

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
