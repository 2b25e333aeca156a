//! Checks that a written report holds together: every relative link and
//! image of every Markdown page under the report folder names a file that
//! exists, and every `#anchor` a heading of the page it points to. The
//! harness runs it after writing a report and refuses a broken one.

use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// The targets of the Markdown links and images of `text`: what stands
/// between `](` and the next `)`.
pub fn link_targets(text: &str) -> Vec<&str> {
    let mut targets = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find("](") {
        let after = &rest[start + 2..];
        let Some(end) = after.find(')') else { break };
        targets.push(&after[..end]);
        rest = &after[end..];
    }
    targets
}

/// The anchor GitHub gives a heading: lower case, punctuation other than
/// `-` and `_` dropped, spaces turned into `-`.
pub fn heading_anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of the headings of a Markdown page.
fn anchors(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| heading_anchor(l.trim_start_matches('#')))
        .collect()
}

/// The Markdown pages under `dir`, recursively, sorted.
fn pages(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let path = entry?.path();
        if path.is_dir() {
            out.extend(pages(&path)?);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
    out.sort();
    Ok(out)
}

/// Every broken link of the report in `dir`, as `page: target (why)`.
/// Links to web addresses are not followed.
pub fn broken_links(dir: &Path) -> Result<Vec<String>> {
    let mut broken = Vec::new();
    for page in pages(dir)? {
        let text = std::fs::read_to_string(&page)
            .with_context(|| format!("reading {}", page.display()))?;
        let here = page.parent().unwrap_or(dir);
        let shown = page
            .strip_prefix(dir)
            .unwrap_or(&page)
            .display()
            .to_string();
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (file, anchor) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target, None),
            };
            let linked = if file.is_empty() {
                page.clone()
            } else {
                here.join(file)
            };
            if !linked.exists() {
                broken.push(format!("{shown}: {target} (no such file)"));
                continue;
            }
            if let Some(anchor) = anchor {
                let linked_text = if file.is_empty() {
                    text.clone()
                } else {
                    std::fs::read_to_string(&linked).unwrap_or_default()
                };
                if !anchors(&linked_text).iter().any(|a| a == anchor) {
                    broken.push(format!("{shown}: {target} (no such heading)"));
                }
            }
        }
    }
    Ok(broken)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_links_and_images() {
        let text = "see [a](a.md) and ![b](img/b.svg), [web](https://x.org) [c](#top)";
        assert_eq!(
            link_targets(text),
            ["a.md", "img/b.svg", "https://x.org", "#top"]
        );
    }

    #[test]
    fn anchors_follow_github() {
        assert_eq!(heading_anchor(" `spring`"), "spring");
        assert_eq!(
            heading_anchor(" Speed against accuracy"),
            "speed-against-accuracy"
        );
        assert_eq!(heading_anchor(" e = 0.8, x_end"), "e--08-x_end");
    }

    #[test]
    fn reports_missing_files_and_headings_only() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("cases")).unwrap();
        std::fs::write(dir.path().join("chart.svg"), "<svg/>").unwrap();
        std::fs::write(
            dir.path().join("README.md"),
            "# Top\n\n[ok](cases/a.md#rows) ![ok](chart.svg) [up](#top)\n\
             [gone](missing.svg) [bad](cases/a.md#nowhere) [web](https://example.org/x)\n",
        )
        .unwrap();
        std::fs::write(
            dir.path().join("cases/a.md"),
            "# A\n\n## Rows\n\n[back](../README.md)\n",
        )
        .unwrap();
        let broken = broken_links(dir.path()).unwrap();
        assert_eq!(
            broken,
            [
                "README.md: missing.svg (no such file)",
                "README.md: cases/a.md#nowhere (no such heading)"
            ]
        );
    }
}
