//! Chapter copies (CI's `grade --check-copies`, `tests/chapter_copies/`):
//! each exercise answered with the chapter's own code, pasted or called,
//! which the grade must fail. A copy's WGSL holds both answers; this picks
//! the half a run grades.

/// The line of a chapter copy (`tests/chapter_copies/lesson_NN.wgsl`, CI's
/// `grade --check-copies`) after which each exercise is answered again,
/// with a call of the lesson's own function in place of a pasted listing.
pub const CHAPTER_COPY_CALLS: &str = "// ==== calls the lesson's own functions ====";

/// Whether this run grades the chapter copies that call the lesson's own
/// functions (`WORKBOOK_CHAPTER_COPY=calls`, set by `grade --check-copies`
/// for its second pass) rather than those that paste its listings. Only
/// builds with `--features chapter_copies` read it.
pub fn chapter_copy_calls() -> bool {
    std::env::var("WORKBOOK_CHAPTER_COPY").is_ok_and(|v| v == "calls")
}

/// A chapter copy's WGSL holds both answers to each exercise, the pasted
/// listings, then after [`CHAPTER_COPY_CALLS`] the calls: the half this run
/// grades ([`chapter_copy_calls`]), the other half's lines left blank so
/// that an error keeps its line number. Any other file is compiled as it is.
pub fn chapter_copy_half<'a>(path: &str, text: &'a str) -> std::borrow::Cow<'a, str> {
    let Some(at) = text.find(CHAPTER_COPY_CALLS) else {
        return text.into();
    };
    if !path.starts_with("tests/chapter_copies/") {
        return text.into();
    }
    let blank = |t: &str| "\n".repeat(t.matches('\n').count());
    let (pasted, calls) = text.split_at(at);
    if chapter_copy_calls() {
        format!("{}{calls}", blank(pasted)).into()
    } else {
        format!("{pasted}{}", blank(calls)).into()
    }
}
