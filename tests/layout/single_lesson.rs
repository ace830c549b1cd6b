//! No module of `common/` serves a single lesson: used by exactly one
//! lesson folder and by no other module of `common/`.

use std::collections::{BTreeMap, BTreeSet};

use crate::lesson_order::lesson_of;
use crate::{module_name, read, repo_root, rust_files};

/// For each common module: the lesson folders and the other common
/// modules that use it.
fn common_users(
    common: &[(String, String)],
    lessons: &[(u32, String)],
) -> BTreeMap<String, (BTreeSet<u32>, BTreeSet<String>)> {
    let mut users = BTreeMap::new();
    for (m, _) in common {
        let by_lessons = lessons
            .iter()
            .filter(|(_, text)| {
                text.contains(&format!("common::{m}::"))
                    || text.contains(&format!("common::{m};"))
                    || text.contains(&format!("common::{{{m}"))
            })
            .map(|(n, _)| *n)
            .collect();
        let by_common = common
            .iter()
            .filter(|(other, text)| {
                other != m
                    && (text.contains(&format!("crate::{m}::"))
                        || text.contains(&format!("crate::{m};")))
            })
            .map(|(other, _)| other.clone())
            .collect();
        users.insert(m.clone(), (by_lessons, by_common));
    }
    users
}

fn single_lesson_modules(
    users: &BTreeMap<String, (BTreeSet<u32>, BTreeSet<String>)>,
) -> Vec<String> {
    users
        .iter()
        .filter(|(_, (l, c))| l.len() == 1 && c.is_empty())
        .map(|(m, (l, _))| {
            format!(
                "common::{m} is used only by lesson {:02}",
                l.first().unwrap_or(&0)
            )
        })
        .collect()
}

#[test]
fn single_lesson_checker_works() {
    let common = vec![
        ("render".to_string(), "use crate::camera::x;".to_string()),
        ("camera".to_string(), String::new()),
        ("cube".to_string(), String::new()),
        ("gpu".to_string(), String::new()),
    ];
    let lessons = vec![
        (
            4,
            "use common::cube::Cube;\nuse common::gpu::Gpu;".to_string(),
        ),
        (
            5,
            "use common::gpu::Gpu;\nuse common::camera::light;".to_string(),
        ),
    ];
    let users = common_users(&common, &lessons);
    let single = single_lesson_modules(&users);
    assert_eq!(
        single,
        ["common::cube is used only by lesson 04"],
        "{users:?}"
    );
}

#[test]
fn no_common_module_serves_a_single_lesson() {
    let src = repo_root().join("common/src");
    let common: Vec<(String, String)> = rust_files(&src)
        .iter()
        .filter_map(|p| Some((module_name(p, &src, "lib.rs")?, read(p))))
        .collect();
    let root = repo_root().join("lessons");
    let mut lessons: BTreeMap<u32, String> = BTreeMap::new();
    for p in rust_files(&root) {
        if let Some(n) = lesson_of(&p, &root) {
            lessons.entry(n).or_default().push_str(&read(&p));
        }
    }
    let lessons: Vec<(u32, String)> = lessons.into_iter().collect();
    assert!(lessons.len() >= 8, "found {} lesson folders", lessons.len());
    let users = common_users(&common, &lessons);
    assert!(
        users.values().any(|(l, _)| l.len() >= 8),
        "no common module is used by every lesson: the checker finds nothing"
    );
    let single = single_lesson_modules(&users);
    assert!(single.is_empty(), "{}", single.join("\n"));
}
