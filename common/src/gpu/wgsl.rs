//! A WGSL module built from named files, checked with naga before wgpu
//! sees it, so that an error names the file and line it is in
//! (`shaders/lesson_01/exercises.wgsl:14:9`), not the line of the joined
//! module (`wgsl:431:9`), which no file has.

use std::fmt;

use naga;

use crate::gpu::Gpu;

/// The WGSL files of one module, in order, joined into one source.
#[derive(Default)]
pub struct WgslSource {
    text: String,
    files: Vec<Part>,
}

/// Where one file sits in the joined source.
struct Part {
    path: String,
    /// Byte offset of the file's first character in the joined source.
    start: usize,
    /// Line of the joined source (1-based) that is the file's line 1.
    first_line: u32,
}

/// A place in one of the files: its path, line and column (1-based).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileLocation {
    pub path: String,
    pub line: u32,
    pub column: u32,
}

impl fmt::Display for FileLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.path, self.line, self.column)
    }
}

/// A WGSL error, located in the file it came from. Its `Display` is one
/// line; [`WgslError::detail`] is the compiler's message with the line,
/// which a lesson prints before that line.
#[derive(Debug)]
pub struct WgslError {
    pub label: String,
    pub location: Option<FileLocation>,
    pub message: String,
    detail: Vec<String>,
}

impl fmt::Display for WgslError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.location {
            Some(at) => write!(f, "WGSL error at {at}: {}", self.message),
            None => write!(f, "WGSL error in {}: {}", self.label, self.message),
        }
    }
}

impl std::error::Error for WgslError {}

impl WgslError {
    /// The compiler's message: the line in its own file with a caret
    /// under the error, and each of the compiler's labels.
    pub fn detail(&self) -> &[String] {
        &self.detail
    }
}

impl WgslSource {
    pub fn new() -> WgslSource {
        WgslSource::default()
    }

    /// Appends one file, named by its path from the repository root.
    pub fn push(&mut self, path: &str, text: &str) {
        // A header line, so the joined source still says whose lines follow.
        self.text += &format!("// ---- {path} ----\n");
        let first_line = self.text.matches('\n').count() as u32 + 1;
        self.files.push(Part {
            path: path.to_string(),
            start: self.text.len(),
            first_line,
        });
        self.text += text;
        if !text.ends_with('\n') {
            self.text.push('\n');
        }
    }

    /// The joined source, as wgpu compiles it.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The file, line and column of a byte offset into the joined source.
    pub fn locate(&self, offset: usize) -> Option<FileLocation> {
        let part = self.files.iter().rev().find(|p| p.start <= offset)?;
        let loc = naga::Span::new(offset as u32, offset as u32).location(&self.text);
        Some(FileLocation {
            path: part.path.clone(),
            line: loc.line_number - part.first_line + 1,
            column: loc.line_position,
        })
    }

    /// Parses and validates the module with naga; an error names the file,
    /// line and column it is in.
    pub fn check(&self, label: &str) -> Result<(), WgslError> {
        let module = match naga::front::wgsl::parse_str(&self.text) {
            Ok(m) => m,
            Err(e) => {
                let labels: Vec<(naga::Span, String)> =
                    e.labels().map(|(s, l)| (s, l.to_string())).collect();
                return Err(self.error(label, e.message().to_string(), &labels));
            }
        };
        let flags = naga::valid::ValidationFlags::all();
        let caps = naga::valid::Capabilities::all();
        if let Err(e) = naga::valid::Validator::new(flags, caps).validate(&module) {
            // The error and its causes, as one sentence.
            let mut message = e.as_inner().to_string();
            let mut source = std::error::Error::source(e.as_inner());
            while let Some(s) = source {
                message += &format!(": {s}");
                source = s.source();
            }
            // The spans run from the function to the expression: the
            // innermost is where the error is.
            let mut labels: Vec<(naga::Span, String)> = e.spans().cloned().collect();
            labels.reverse();
            return Err(self.error(label, message, &labels));
        }
        Ok(())
    }

    /// Checks the module, then compiles it on the device.
    pub fn shader_module(&self, gpu: &Gpu, label: &str) -> Result<wgpu::ShaderModule, WgslError> {
        self.check(label)?;
        Ok(gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(self.text.as_str().into()),
            }))
    }

    fn error(&self, label: &str, message: String, labels: &[(naga::Span, String)]) -> WgslError {
        let first = labels.iter().find_map(|(s, _)| s.to_range());
        let location = first.as_ref().and_then(|r| self.locate(r.start));
        let mut detail = Vec::new();
        if let (Some(at), Some(r)) = (&location, first) {
            // The line as it is in its own file, with a caret under the span.
            let line_start = self.text[..r.start].rfind('\n').map_or(0, |i| i + 1);
            let line_end = self.text[r.start..]
                .find('\n')
                .map_or(self.text.len(), |i| r.start + i);
            let line = &self.text[line_start..line_end];
            let width = at.line.to_string().len();
            let col = self.text[line_start..r.start].chars().count();
            let len = self.text[r.start..r.end.min(line_end)]
                .chars()
                .count()
                .max(1);
            detail.push(format!("{:width$}--> {at}", ""));
            detail.push(format!("{:width$} |", ""));
            detail.push(format!("{} | {line}", at.line));
            detail.push(format!(
                "{:width$} | {}{}",
                "",
                " ".repeat(col),
                "^".repeat(len)
            ));
        }
        for (span, text) in labels {
            // naga names its IR handles (`naga::ir::Expression [6]`): no use here.
            if text.is_empty() || text.starts_with("naga::") {
                continue;
            }
            match span.to_range().and_then(|r| self.locate(r.start)) {
                Some(at) => detail.push(format!("{at}: {text}")),
                None => detail.push(text.clone()),
            }
        }
        WgslError {
            label: label.to_string(),
            location,
            message,
            detail,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const COMMON: &str = include_str!("../../../shaders/common.wgsl");

    /// The module a lesson's exercise is compiled in, with one line of the
    /// exercise file replaced by `broken`.
    fn with_broken_line(lesson: &str, exercises: &str, line: usize, broken: &str) -> WgslSource {
        let mut edited: Vec<&str> = exercises.lines().collect();
        edited[line - 1] = broken;
        let mut source = WgslSource::new();
        source.push("shaders/common.wgsl", COMMON);
        source.push(&format!("shaders/{lesson}/before.wgsl"), "fn before() {}\n");
        source.push(
            &format!("shaders/{lesson}/exercises.wgsl"),
            &edited.join("\n"),
        );
        source.push(&format!("shaders/{lesson}/after.wgsl"), "fn after() {}\n");
        source
    }

    /// A broken line of each chapter's `exercises.wgsl` is reported at its
    /// own file and line, not at the line of the joined module.
    #[test]
    fn a_broken_exercise_line_is_reported_in_its_own_file() {
        let files = [
            (
                "lesson_01",
                include_str!("../../../shaders/lesson_01/exercises.wgsl"),
            ),
            (
                "lesson_02",
                include_str!("../../../shaders/lesson_02/exercises.wgsl"),
            ),
            (
                "lesson_03",
                include_str!("../../../shaders/lesson_03/exercises.wgsl"),
            ),
            (
                "lesson_04",
                include_str!("../../../shaders/lesson_04/exercises.wgsl"),
            ),
        ];
        for (lesson, text) in files {
            // The first line inside a function's body.
            let fn_line = text
                .lines()
                .position(|l| l.starts_with("fn ") && l.trim_end().ends_with('{'))
                .expect("the file has a function");
            let line = fn_line + 2;
            let source = with_broken_line(lesson, text, line, "    let broken = ;");
            let e = source.check(lesson).expect_err("a broken line must fail");
            let at = e.location.clone().expect("the error has a location");
            assert_eq!(at.path, format!("shaders/{lesson}/exercises.wgsl"), "{e}");
            assert_eq!(at.line as usize, line, "{e}");
            assert_eq!(at.column, 18, "{e}");
            assert!(
                e.to_string().starts_with(&format!(
                    "WGSL error at shaders/{lesson}/exercises.wgsl:{line}:18: "
                )),
                "{e}"
            );
            assert!(
                e.detail().iter().any(|l| l.contains("let broken = ;")),
                "{e:?}"
            );
        }
    }

    /// A validation error (not a syntax error) is located the same way.
    #[test]
    fn a_type_error_is_reported_in_its_own_file() {
        let mut source = WgslSource::new();
        source.push("shaders/common.wgsl", COMMON);
        source.push(
            "shaders/x/exercises.wgsl",
            "fn f() -> f32 {\n    return 1u;\n}\n",
        );
        let e = source.check("x").expect_err("returning u32 from f32 fails");
        let at = e.location.expect("located");
        assert_eq!(
            (at.path.as_str(), at.line),
            ("shaders/x/exercises.wgsl", 2),
            "{}",
            e.message
        );
    }
}
