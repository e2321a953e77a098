//! One source of truth for the verdicts the documentation quotes: `docs/claims.md` is the
//! claims table that `trirhythm report` wrote at full quality (pasted unchanged, its first
//! line naming the commit and the data), and every other place that states a computed verdict
//! quotes it: the README's counts, and each `` `claim-id` **verdict** `` of docs/findings.md.
//! Checked here: the snapshot has one row for each claim of the registry and no other (a new
//! or renamed claim needs a new report), its counts are its rows', the README's counts are
//! its counts, every claim is named in findings.md with its verdict, no verdict there differs
//! from the snapshot's, and findings.md states no verdict in bold without its claim's id.

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use trirhythm_paper::verdict::claims::registry;

const VERDICTS: [&str; 3] = ["confirmed", "refuted", "undetermined"];

fn doc(path: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// (claim id → verdict) of a claims table written by `report`.
fn snapshot() -> (String, BTreeMap<String, String>) {
    let md = doc("docs/claims.md");
    let head = md.lines().next().unwrap_or_default().to_string();
    let mut rows = BTreeMap::new();
    for line in md.lines().filter(|l| l.starts_with("| `")) {
        let id = line[3..].split('`').next().unwrap().to_string();
        let cells: Vec<&str> = line.split(" | ").collect();
        let verdict = VERDICTS
            .iter()
            .find(|v| {
                cells
                    .get(2)
                    .is_some_and(|c| c.starts_with(&format!("**{v}**")))
            })
            .unwrap_or_else(|| panic!("{id}: no verdict in its row: {line}"));
        assert!(
            rows.insert(id.clone(), verdict.to_string()).is_none(),
            "{id} twice in docs/claims.md"
        );
    }
    (head, rows)
}

/// The counts `N confirmed, M refuted, K undetermined` the first time `text` states them.
fn counts_in(text: &str) -> [usize; 3] {
    let at = text
        .find(" confirmed, ")
        .expect("a sentence with the counts");
    let before: String = text[..at]
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    let c: usize = before.chars().rev().collect::<String>().parse().unwrap();
    let rest = &text[at + " confirmed, ".len()..];
    let number = |s: &str| -> (usize, usize) {
        let digits: String = s.chars().take_while(|c| c.is_ascii_digit()).collect();
        (digits.parse().unwrap(), digits.len())
    };
    let (r, n) = number(rest);
    let rest = rest[n..]
        .strip_prefix(" refuted, ")
        .expect("N confirmed, M refuted, K undetermined");
    let (u, _) = number(rest);
    [c, r, u]
}

#[test]
fn the_docs_quote_the_verdicts_of_the_full_quality_report() {
    let (head, rows) = snapshot();
    assert!(
        head.starts_with("Claims of the paper decided by trirhythm (")
            && head.contains("full quality"),
        "docs/claims.md is not a full-quality report's table: {head}"
    );
    let ids: BTreeSet<String> = registry().into_iter().map(|c| c.id).collect();
    let listed: BTreeSet<String> = rows.keys().cloned().collect();
    assert_eq!(
        listed, ids,
        "docs/claims.md and the registry differ: write the report again"
    );
    let tally = |v: &str| rows.values().filter(|x| *x == v).count();
    let counts = [tally("confirmed"), tally("refuted"), tally("undetermined")];
    assert_eq!(
        counts_in(&head),
        counts,
        "docs/claims.md: its head against its rows"
    );
    let readme = doc("README.md");
    assert_eq!(
        counts_in(&readme),
        counts,
        "README's counts against docs/claims.md"
    );

    let findings = doc("docs/findings.md");
    // every bold verdict word follows its claim's id, and agrees with the snapshot
    let mut named = BTreeSet::new();
    for (i, _) in findings.match_indices("**") {
        let after = &findings[i + 2..];
        let Some(word) = VERDICTS
            .iter()
            .chain(&["holds", "does not hold", "Holds", "Does not hold"])
            .find(|w| after.starts_with(&format!("{w}**")))
        else {
            continue;
        };
        let before = findings[..i].trim_end();
        let id = before
            .strip_suffix('`')
            .and_then(|b| b.rfind('`').map(|j| &b[j + 1..]))
            .unwrap_or_else(|| {
                panic!(
                    "docs/findings.md: a verdict in bold without its claim's id: …{}**{word}**",
                    &before[before.len().saturating_sub(60)..]
                )
            });
        let expected = rows
            .get(id)
            .unwrap_or_else(|| panic!("docs/findings.md names `{id}`, no claim of the report"));
        assert_eq!(
            *word,
            expected.as_str(),
            "docs/findings.md says `{id}` **{word}**, the report {expected}"
        );
        named.insert(id.to_string());
    }
    let missing: Vec<&String> = ids.iter().filter(|id| !named.contains(*id)).collect();
    assert!(
        missing.is_empty(),
        "docs/findings.md states no verdict for {missing:?}"
    );
}
