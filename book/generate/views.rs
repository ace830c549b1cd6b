//! A chapter's view of a generated table: the rows and columns its text
//! points at, cut from the full table that its lesson's record page shows.
//! A chapter never types a measured table: it declares the view, and
//! `workbook book` / `workbook tables` / `workbook fill` writes the table
//! between the markers.
//!
//! ```text
//! <!--view: lesson_01/results.md rows: res_256; res_4096 cols: variant; false shadow %; GPU ms-->
//! (the generator writes the source's header line, the cut table and the
//! legend of the columns kept here)
//! <!--/view-->
//! ```
//!
//! The declaration is one line (a comment in the book closes on its line).
//! It names a generated table (a path under
//! `book/src/generated/`); then `rows:` lists the rows to keep, in the order to
//! show them, by their first cell (backticks left out; leave the line out
//! for every row); `cols:` the columns, by their heading (backticks left
//! out, `|` for `\|`); `table: N` picks the Nth table of a file that holds
//! several (1 by default). Items are separated by `;`, since headings hold
//! commas. A row or a column the table lacks is an error, never an empty
//! cell.
//!
//! `tests/book_views.rs` fails when a view's table is not what its source
//! makes today.

use std::path::Path;

use anyhow::{bail, Context, Result};

/// Opens a view: `<!--view: SOURCE`.
pub const OPEN: &str = "<!--view:";
/// Closes a view's table.
pub const CLOSE: &str = "<!--/view-->";

/// What a view keeps of its source.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The generated file, relative to `book/src/generated/`.
    pub source: String,
    /// Which table of the file, from 1.
    pub table: usize,
    /// The rows to keep, by first cell; `None` keeps every row.
    pub rows: Option<Vec<String>>,
    /// The columns to keep, by heading.
    pub cols: Vec<String>,
}

/// Reads a view's declaration: the text between `<!--view:` and `-->`,
/// `SOURCE rows: A; B cols: X; Y table: N` (on one line, since a comment
/// inside the book's paragraphs must close on its line; line breaks are
/// read as spaces).
pub fn parse_spec(key: &str) -> Result<Spec> {
    let key = key.split_whitespace().collect::<Vec<_>>().join(" ");
    let fields = ["rows:", "cols:", "table:"];
    // Where each field starts, in the order written.
    let mut starts: Vec<(usize, &str)> = fields
        .iter()
        .filter_map(|f| {
            key.match_indices(f)
                .find(|(i, _)| *i == 0 || key.as_bytes()[i - 1] == b' ')
                .map(|(i, _)| (i, *f))
        })
        .collect();
    starts.sort();
    let source = key[..starts.first().map_or(key.len(), |s| s.0)].trim();
    if source.is_empty() {
        bail!("a view names its source first: `<!--view: lesson_NN/results.md cols: ...-->`");
    }
    if source.contains(' ') {
        bail!("`{source}`: after the source come `rows:`, `cols:` or `table:`");
    }
    let list = |s: &str| -> Vec<String> {
        s.split(';')
            .map(|x| x.trim().to_string())
            .filter(|x| !x.is_empty())
            .collect()
    };
    let mut spec = Spec {
        source: source.to_string(),
        table: 1,
        rows: None,
        cols: Vec::new(),
    };
    for (k, &(at, field)) in starts.iter().enumerate() {
        let end = starts.get(k + 1).map_or(key.len(), |s| s.0);
        let value = key[at + field.len()..end].trim();
        match field {
            "rows:" => spec.rows = Some(list(value)),
            "cols:" => spec.cols = list(value),
            _ => {
                spec.table = value
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .with_context(|| format!("`table: {value}` is not a number from 1"))?
            }
        }
    }
    if !spec.source.ends_with(".md") {
        bail!(
            "`{}`: a view's source is a generated table (`.md`)",
            spec.source
        );
    }
    if spec.cols.is_empty() {
        bail!(
            "`{}`: the view lists no columns (`cols: variant; ...`)",
            spec.source
        );
    }
    Ok(spec)
}

/// The cells of a markdown table row, `\|` kept inside its cell.
pub fn cells(line: &str) -> Vec<String> {
    let t = line.trim();
    let t = t.strip_prefix('|').unwrap_or(t);
    let t = t.strip_suffix('|').unwrap_or(t);
    let mut out = vec![String::new()];
    let mut chars = t.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                chars.next();
                out.last_mut().expect("one cell").push_str("\\|");
            }
            '|' => out.push(String::new()),
            c => out.last_mut().expect("one cell").push(c),
        }
    }
    out.into_iter().map(|c| c.trim().to_string()).collect()
}

/// A cell or heading as a view names it: no backticks, `|` unescaped.
pub fn plain(cell: &str) -> String {
    cell.replace('`', "").replace("\\|", "|").trim().to_string()
}

/// One table of a generated file: the header line above it (the adapter,
/// the resolution, the protocol), its rows, and its legend's entries.
struct Source {
    header: Option<String>,
    /// The bold lead of the paragraph that opens this table's part of the
    /// file (`**NVIDIA H200, Vulkan, the code of commit ...**`), where a
    /// file holds one table per adapter.
    part: Option<String>,
    rows: Vec<Vec<String>>,
    legend: Vec<String>,
}

fn source_table(text: &str, n: usize) -> Result<Source> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = 0;
    let mut i = 0;
    let mut previous_end = 0;
    while i < lines.len() {
        if !lines[i].trim_start().starts_with('|') {
            i += 1;
            continue;
        }
        let start = i;
        while i < lines.len() && lines[i].trim_start().starts_with('|') {
            i += 1;
        }
        found += 1;
        if found < n {
            previous_end = i;
            continue;
        }
        let part = lines[previous_end..start]
            .iter()
            .rev()
            .map(|l| l.trim())
            .find_map(|l| {
                let rest = l.strip_prefix("**")?;
                let end = rest.find("**")?;
                Some(format!("**{}**", &rest[..end]))
            });
        let header = lines[..start]
            .iter()
            .rev()
            .map(|l| l.trim())
            .find(|l| l.starts_with('*') && l.ends_with('*') && !l.starts_with("**"))
            .map(str::to_string);
        let rows: Vec<Vec<String>> = lines[start..i]
            .iter()
            .enumerate()
            .filter(|(k, _)| *k != 1) // the `| --- |` line
            .map(|(_, l)| cells(l))
            .collect();
        // The legend: the `<details>` block right under the table.
        let mut legend = Vec::new();
        let mut j = i;
        while j < lines.len() && lines[j].trim().is_empty() {
            j += 1;
        }
        if j < lines.len() && lines[j].trim_start().starts_with("<details>") {
            j += 1;
            while j < lines.len() && !lines[j].trim_start().starts_with("</details>") {
                if lines[j].starts_with("- ") {
                    legend.push(lines[j].to_string());
                }
                j += 1;
            }
        }
        return Ok(Source {
            header,
            part,
            rows,
            legend,
        });
    }
    bail!("it has {found} table(s), not {n}");
}

/// The view's text, between its markers, from its source's text.
pub fn render(spec: &Spec, source: &str) -> Result<String> {
    let t = source_table(source, spec.table).with_context(|| spec.source.clone())?;
    let head = &t.rows[0];
    let mut cols = Vec::new();
    for c in &spec.cols {
        let Some(k) = head.iter().position(|h| plain(h) == *c) else {
            let have: Vec<String> = head.iter().map(|h| plain(h)).collect();
            bail!(
                "{}: no column `{c}` (it has: {})",
                spec.source,
                have.join("; ")
            );
        };
        cols.push(k);
    }
    let body = &t.rows[1..];
    let rows: Vec<&Vec<String>> = match &spec.rows {
        None => body.iter().collect(),
        Some(names) => {
            let mut kept = Vec::new();
            for name in names {
                let Some(r) = body.iter().find(|r| plain(&r[0]) == *name) else {
                    let have: Vec<String> = body.iter().map(|r| plain(&r[0])).collect();
                    bail!(
                        "{}: no row `{name}` (it has: {})",
                        spec.source,
                        have.join("; ")
                    );
                };
                kept.push(r);
            }
            kept
        }
    };
    let line = |r: &Vec<String>| -> String {
        let picked: Vec<&str> = cols
            .iter()
            .map(|&k| r.get(k).map_or("", String::as_str))
            .collect();
        format!("| {} |\n", picked.join(" | "))
    };
    let mut s = String::from("\n");
    if let Some(p) = &t.part {
        s += &format!("{p}\n\n");
    }
    if let Some(h) = &t.header {
        s += &format!("{}\n\n", header_for(h, &spec.cols));
    }
    s += &line(head);
    s += &format!("|{}\n", " --- |".repeat(cols.len()));
    for r in rows {
        s += &line(r);
    }
    let names: Vec<String> = cols.iter().map(|&k| head[k].clone()).collect();
    let legend: Vec<&String> = t
        .legend
        .iter()
        .filter(|l| names.iter().any(|n| l.starts_with(&format!("- {n}: "))))
        .collect();
    if !legend.is_empty() {
        s += "\n<details><summary>What each column means</summary>\n\n";
        for l in legend {
            s += &format!("{l}\n");
        }
        s += "\n</details>\n";
    }
    s += "\n";
    Ok(s)
}

/// Whether a column holds a time: its cells are medians with spreads.
fn is_time(col: &str) -> bool {
    col.ends_with(" ms")
        || col.contains("(ms)")
        || col.starts_with("shadows cost")
        || col == "vs the fastest"
}

/// The source's header line, less its timing protocol when the view keeps
/// no time: a reader should not look for times the view does not show.
fn header_for(header: &str, cols: &[String]) -> String {
    match header.find(" · times: ") {
        Some(at) if !cols.iter().any(|c| is_time(c)) => format!("{}*", &header[..at]),
        _ => header.to_string(),
    }
}

/// Every view in `text`: (line, declaration, its current body).
pub fn views(text: &str) -> Result<Vec<(usize, String, String)>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(OPEN) {
        let line = text[..text.len() - rest.len() + at].lines().count() + 1;
        let after = &rest[at + OPEN.len()..];
        let Some(end_key) = after.find("-->") else {
            bail!("line {line}: a `{OPEN}` without `-->`");
        };
        let body_start = &after[end_key + 3..];
        let Some(end_body) = body_start.find(CLOSE) else {
            bail!("line {line}: a view without `{CLOSE}`");
        };
        if body_start[..end_body].contains(OPEN) {
            bail!("line {line}: a view without `{CLOSE}` before the next view");
        }
        out.push((
            line,
            after[..end_key].to_string(),
            body_start[..end_body].to_string(),
        ));
        rest = &body_start[end_body + CLOSE.len()..];
    }
    Ok(out)
}

/// `text` with every view's body written from `read(source)`.
pub fn fill(text: &str, read: &mut dyn FnMut(&str) -> Result<String>) -> Result<String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    for (line, key, _) in views(text)? {
        let at = rest.find(OPEN).expect("views() found it");
        let after = &rest[at + OPEN.len()..];
        let end_key = after.find("-->").expect("views() found it");
        let body_start = &after[end_key + 3..];
        let end_body = body_start.find(CLOSE).expect("views() found it");
        let spec = parse_spec(&key).with_context(|| format!("line {line}: the view"))?;
        let source = read(&spec.source).with_context(|| format!("line {line}: {}", spec.source))?;
        let body = render(&spec, &source).with_context(|| format!("line {line}"))?;
        out.push_str(&rest[..at]);
        out.push_str(OPEN);
        out.push_str(&key);
        out.push_str("-->");
        out.push_str(&body);
        out.push_str(CLOSE);
        rest = &body_start[end_body + CLOSE.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

/// A generated file's text, for [`fill`].
pub fn read_generated(generated: &Path, source: &str) -> Result<String> {
    let path = generated.join(source);
    std::fs::read_to_string(&path).with_context(|| format!("no generated table {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::measure::counters::DRAWS;

    const SOURCE: &str = "*llvmpipe, Vulkan · 640×360*\n\n\
| variant | misclassified % | `draws` | mean \\|ΔV\\| % | frame ms |\n\
| --- | --- | --- | --- | --- |\n\
| no shadows (baseline) | — | — | — | 1.0 [0.9–1.1] |\n\
| `a` | 1.000 | 3 | 0.5 | 2.0 [1.9–2.1] |\n\
| `b` | 2.000 | 4 | 0.7 | 3.0 [2.9–3.1] |\n\n\
<details><summary>What each column means</summary>\n\n\
- variant: the variant\n- misclassified %: wrong pixels\n- `draws`: draw calls\n\
- mean \\|ΔV\\| %: the mean\n- frame ms: the frame\n\n</details>\n";

    #[test]
    fn a_view_keeps_its_rows_and_columns_in_its_order() {
        let spec = parse_spec(" lesson_01/results.md rows: b; a cols: variant; mean |ΔV| %; draws")
            .unwrap();
        let got = render(&spec, SOURCE).unwrap();
        assert!(got.contains("*llvmpipe, Vulkan · 640×360*"), "{got}");
        assert!(
            got.contains(
                "| variant | mean \\|ΔV\\| % | `draws` |\n| --- | --- | --- |\n| `b` | 0.7 | 4 |\n| `a` | 0.5 | 3 |\n"
            ),
            "{got}"
        );
        assert!(got.contains("- `draws`: draw calls"), "{got}");
        assert!(!got.contains("- frame ms"), "{got}");
    }

    #[test]
    fn a_view_without_times_drops_the_protocol() {
        let h = "*lavapipe · 640×360 · times: median [spread] of 3 runs × 5 frames*";
        let cols = |c: &[&str]| c.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(
            header_for(h, &cols(&["variant", DRAWS.name])),
            "*lavapipe · 640×360*"
        );
        assert_eq!(header_for(h, &cols(&["variant", "GPU ms"])), h);
        assert_eq!(header_for(h, &cols(&["variant", "`shadow` ms"])), h);
    }

    #[test]
    fn a_view_of_a_later_table_names_its_part() {
        let two = format!(
            "{SOURCE}\n**NVIDIA H200, Vulkan**: the second set.\n\n| variant | draws |\n| --- | --- |\n| `a` | 9 |\n"
        );
        let spec = parse_spec("x.md cols: variant; draws table: 2").unwrap();
        let got = render(&spec, &two).unwrap();
        assert!(got.contains("**NVIDIA H200, Vulkan**\n"), "{got}");
        assert!(got.contains("| `a` | 9 |"), "{got}");
        let first = render(&parse_spec("x.md cols: variant").unwrap(), &two).unwrap();
        assert!(!first.contains("H200"), "{first}");
    }

    #[test]
    fn a_missing_row_or_column_is_an_error() {
        let spec = parse_spec("x.md rows: c cols: variant").unwrap();
        assert!(render(&spec, SOURCE)
            .unwrap_err()
            .to_string()
            .contains("no row `c`"));
        let spec = parse_spec("x.md cols: variant; GPU ms").unwrap();
        assert!(render(&spec, SOURCE)
            .unwrap_err()
            .to_string()
            .contains("no column `GPU ms`"));
        assert!(parse_spec("x.md row: a cols: variant").is_err());
        assert_eq!(parse_spec("x.md cols: a table: 2").unwrap().table, 2);
        assert!(parse_spec("x.md").is_err());
    }

    #[test]
    fn fill_writes_the_body_and_keeps_the_rest() {
        let page = "before\n\n<!--view: x.md rows: a cols: variant; draws-->\nstale\n<!--/view-->\nafter\n";
        let got = fill(page, &mut |_| Ok(SOURCE.to_string())).unwrap();
        assert!(got.starts_with("before\n\n<!--view: x.md rows: a cols: variant; draws-->\n"));
        assert!(got.contains("| `a` | 3 |\n"), "{got}");
        assert!(!got.contains("stale"));
        assert!(got.ends_with("<!--/view-->\nafter\n"));
        // Filling twice changes nothing.
        assert_eq!(fill(&got, &mut |_| Ok(SOURCE.to_string())).unwrap(), got);
    }
}
