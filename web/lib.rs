//! The web build's entry: every lesson's own `main.rs` (its variants and
//! its `Lesson`), compiled into one module, and [`run_lesson`], which the
//! book's page calls with the lesson's name. Each lesson's `main` runs its
//! window in the page's canvas (`common::run::web`).
#![cfg(target_arch = "wasm32")]
// A lesson's harness that the web build does not call (`write_extras`'
// files, the exercises' grading hooks) is dead code here, not on the desktop.
#![allow(dead_code)]

use wasm_bindgen::prelude::*;

#[path = "../lessons/lesson_01/main.rs"]
mod lesson_01;
#[path = "../lessons/lesson_02/main.rs"]
mod lesson_02;
#[path = "../lessons/lesson_03/main.rs"]
mod lesson_03;
#[path = "../lessons/lesson_04/main.rs"]
mod lesson_04;
#[path = "../lessons/lesson_05/main.rs"]
mod lesson_05;
#[path = "../lessons/lesson_06/main.rs"]
mod lesson_06;
#[path = "../lessons/lesson_07/main.rs"]
mod lesson_07;
#[path = "../lessons/lesson_08/main.rs"]
mod lesson_08;
#[path = "../lessons/lesson_09/main.rs"]
mod lesson_09;
#[path = "../lessons/lesson_10/main.rs"]
mod lesson_10;

/// Runs lesson `name` (`"lesson_05"`) in the page's canvas
/// (`#workbook-canvas`, its flags in `data-args`).
#[wasm_bindgen]
pub fn run_lesson(name: &str) -> Result<(), JsValue> {
    common::run::web::catch_panics();
    let _ = match name {
        "lesson_01" => lesson_01::main(),
        "lesson_02" => lesson_02::main(),
        "lesson_03" => lesson_03::main(),
        "lesson_04" => lesson_04::main(),
        "lesson_05" => lesson_05::main(),
        "lesson_06" => lesson_06::main(),
        "lesson_07" => lesson_07::main(),
        "lesson_08" => lesson_08::main(),
        "lesson_09" => lesson_09::main(),
        "lesson_10" => lesson_10::main(),
        _ => return Err(format!("no lesson {name:?} (lesson_01 … lesson_10)").into()),
    };
    Ok(())
}
