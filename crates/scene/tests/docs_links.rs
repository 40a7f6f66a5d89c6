//! Every relative link in the repository's Markdown (`README.md`, `docs/`, `scripts/`,
//! `assets/`) resolves inside the repository: the file or folder exists, and a `#anchor` into
//! a Markdown file names one of its headings. A clone of this repository alone must have no
//! broken links.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

/// The repository's root, two levels above this crate.
fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the repository root exists")
}

/// The Markdown files whose links are checked: `README.md` and every `.md` under the folders
/// of documentation.
fn markdown_files(root: &Path) -> Vec<PathBuf> {
    let mut files = vec![root.join("README.md")];
    for folder in ["docs", "scripts", "assets"] {
        collect_markdown(&root.join(folder), &mut files);
    }
    files.sort();
    files
}

fn collect_markdown(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.expect("a readable folder entry").path();
        if path.is_dir() {
            collect_markdown(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}

/// The text outside fenced code blocks and inline code spans, where links live.
fn prose(markdown: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in markdown.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if !fenced {
            out.push_str(line);
        }
        out.push('\n');
    }
    without_code_spans(&out)
}

/// `text` with every inline code span (a run of backticks up to the same run) blanked out.
fn without_code_spans(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].len() - rest[start..].trim_start_matches('`').len();
        let fence = &rest[start..start + ticks];
        let after = &rest[start + ticks..];
        match after.find(fence) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                out.push_str(fence);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The targets of inline links and images, `[text](target)`, and of reference definitions,
/// `[label]: target`.
fn link_targets(prose: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = prose;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let end = after.find(')').unwrap_or(after.len());
        let target = after[..end].split_whitespace().next().unwrap_or("");
        targets.push(target.trim_matches(['<', '>']).to_string());
        rest = &after[end..];
    }
    for line in prose.lines() {
        let line = line.trim_start();
        if let Some(close) = line.find("]: ").filter(|_| line.starts_with('[')) {
            let target = line[close + 3..].split_whitespace().next().unwrap_or("");
            targets.push(target.to_string());
        }
    }
    targets
}

/// Whether a link leaves the repository by design: a URL or an e-mail address.
fn is_external(target: &str) -> bool {
    target.contains("://") || target.starts_with("mailto:")
}

/// The anchors GitHub gives a Markdown file's headings: the heading's text lower-cased, code
/// marks and punctuation other than `-` and `_` dropped, spaces made `-`; a repeated
/// heading gets `-1`, `-2`, ...
fn heading_anchors(markdown: &str) -> BTreeSet<String> {
    let mut anchors = BTreeSet::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        let heading = line.trim_start_matches('#');
        if fenced || heading.len() == line.len() || !heading.starts_with(' ') {
            continue;
        }
        let slug: String = heading
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                _ => None,
            })
            .collect();
        let mut unique = slug.clone();
        let mut n = 0;
        while anchors.contains(&unique) {
            n += 1;
            unique = format!("{slug}-{n}");
        }
        anchors.insert(unique);
    }
    anchors
}

/// `path` with `.` and `..` resolved lexically, so a link that climbs out of the repository
/// is caught even where the place outside exists.
fn normalized(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// What is wrong with one link of `file`, if anything.
fn broken(root: &Path, file: &Path, target: &str) -> Option<String> {
    let (path_part, anchor) = match target.split_once('#') {
        Some((p, a)) => (p, Some(a)),
        None => (target, None),
    };
    let resolved = if path_part.is_empty() {
        file.to_path_buf()
    } else if path_part.starts_with('/') {
        return Some("an absolute path: write it relative to the file".into());
    } else {
        normalized(&file.parent().expect("a file has a folder").join(path_part))
    };
    if !resolved.starts_with(root) {
        return Some("points outside the repository".into());
    }
    let shown = resolved.strip_prefix(root).unwrap_or(&resolved).display();
    if !resolved.exists() {
        return Some(format!("{shown} does not exist"));
    }
    let anchor = anchor.filter(|a| !a.is_empty())?;
    if resolved.extension().is_none_or(|e| e != "md") {
        return None;
    }
    let text = std::fs::read_to_string(&resolved).expect("a readable Markdown file");
    let anchors = heading_anchors(&text);
    (!anchors.contains(anchor)).then(|| format!("no heading of {shown} has anchor #{anchor}"))
}

#[test]
fn every_relative_link_in_the_docs_resolves_inside_the_repository() {
    let root = repo_root();
    let mut problems = Vec::new();
    let mut checked = 0;
    for file in markdown_files(&root) {
        let text = std::fs::read_to_string(&file).expect("a readable Markdown file");
        for target in link_targets(&prose(&text)) {
            if target.is_empty() || is_external(&target) {
                continue;
            }
            checked += 1;
            if let Some(why) = broken(&root, &file, &target) {
                let name = file.strip_prefix(&root).unwrap_or(&file).display();
                problems.push(format!("{name}: ({target}): {why}"));
            }
        }
    }
    assert!(
        checked > 10,
        "only {checked} links found: the parser is broken"
    );
    assert!(
        problems.is_empty(),
        "broken links:\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_link_parser_finds_links_and_skips_code() {
    let text = "See [a](a.md#x) and ![b](img/b.png \"t\").\n\
                `[not](code.md)` and\n```\n[not](fenced.md)\n```\n[ref]: r.md\n\
                [split\ntext](split.md)";
    assert_eq!(
        link_targets(&prose(text)),
        ["a.md#x", "img/b.png", "split.md", "r.md"]
    );
}

#[test]
fn anchors_follow_github_headings() {
    let anchors = heading_anchors(
        "# The benchmark scene: `corridor`\n## Videos (`bench --clock real --video DIR`)\n\
         ## Notes\n## Notes\n```\n# not a heading\n```\n",
    );
    let expected: BTreeSet<String> = [
        "the-benchmark-scene-corridor",
        "videos-bench---clock-real---video-dir",
        "notes",
        "notes-1",
    ]
    .into_iter()
    .map(String::from)
    .collect();
    assert_eq!(anchors, expected);
}
