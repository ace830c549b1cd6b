//! `common/src/lib.rs` and each folder's `mod.rs` list every module they
//! have (`pub mod x;`), in their docs too (`[\`x\`]`).

use std::collections::BTreeSet;

use crate::{module_name, read, repo_root, rust_files};

/// `pub mod x;` declarations of a lib.rs.
fn declared_modules(lib: &str) -> BTreeSet<String> {
    lib.lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod "))
        .map(|m| m.trim_end_matches(';').trim().to_string())
        .collect()
}

#[test]
fn common_lib_lists_every_module() {
    let src = repo_root().join("common/src");
    // lib.rs declares the folders; each folder's mod.rs its own modules.
    let mut declared = BTreeSet::new();
    let lib = read(&src.join("lib.rs"));
    let mut roots = vec![(String::new(), src.join("lib.rs"), lib)];
    // Folders within folders: each declared module with a `mod.rs`.
    let mut i = 0;
    while i < roots.len() {
        let (prefix, _, text) = roots[i].clone();
        let dir = src.join(prefix.trim_end_matches("::").replace("::", "/"));
        for g in declared_modules(&text) {
            let root = dir.join(&g).join("mod.rs");
            if root.exists() {
                let text = read(&root);
                roots.push((format!("{prefix}{g}::"), root, text));
            }
        }
        i += 1;
    }
    for (prefix, path, text) in &roots {
        for m in declared_modules(text) {
            assert!(
                text.contains(&format!("[`{m}`]")),
                "{}'s docs do not list [`{m}`]",
                path.display()
            );
            declared.insert(format!("{prefix}{m}"));
        }
    }
    assert!(
        roots.len() >= 4,
        "found {} folders with a mod.rs",
        roots.len() - 1
    );
    let files: BTreeSet<String> = rust_files(&src)
        .iter()
        .filter_map(|p| module_name(p, &src, "lib.rs"))
        .collect();
    assert!(files.len() >= 10, "found {files:?}");
    assert_eq!(
        declared, files,
        "the `pub mod`s of common/src/lib.rs and its folders' mod.rs, and the files of common/src differ"
    );
}
