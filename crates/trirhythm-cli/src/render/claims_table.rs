//! The claims table of a report as Markdown (`claims.md`): one row per claim — its words and
//! place, the verdict (with the first clause of the reason when undetermined; the page has it
//! whole) and its first deciding number — written
//! from the verdicts alone, so that a README or a paper's supplement can carry the table the
//! code decided rather than one typed by hand. Tested in `tests/report.rs` (every claim has a
//! row, the verdict of each row is the page's).

use super::report::spell_undefined;
use trirhythm_paper::verdict::claims::Verdicts;
use trirhythm_paper::verdict::Verdict;

/// A Markdown table cell: pipes escaped, line breaks as spaces.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace(['\n', '\r'], " ")
}

/// The summary clauses of a reason: its first clause and each clause that opens a start's
/// part ("from the rest basin …", "from the outer cycle …"), with " …" where clauses were left
/// out.
fn first_clause(text: &str) -> String {
    let clauses: Vec<&str> = text.split("; ").collect();
    let kept: Vec<&str> = clauses
        .iter()
        .enumerate()
        .filter(|(i, c)| *i == 0 || c.starts_with("from the "))
        .map(|(_, c)| *c)
        .collect();
    let mut out = kept.join("; ");
    if kept.len() < clauses.len() {
        out.push_str(" …");
    }
    out
}

/// The claims table of `verdicts` as Markdown, headed by one line naming what it was computed
/// from (`source`, e.g. "trirhythm 0.1.0, commit …, full quality").
pub fn claims_markdown(verdicts: &Verdicts, source: &str) -> String {
    let (c, r, u) = verdicts.counts();
    let mut out = format!(
        "Claims of the paper decided by trirhythm ({source}): {c} confirmed, {r} refuted, {u} \
         undetermined; {} not decided by code.\n\n\
         | Claim | Where | Verdict | The number that decides it |\n|---|---|---|---|\n",
        verdicts.not_computable.len()
    );
    for v in &verdicts.claims {
        let d = &v.decision;
        let verdict = match &d.verdict {
            Verdict::Undetermined { why } => {
                format!("**undetermined**: {}", first_clause(&spell_undefined(why)))
            }
            other => format!("**{}**", other.tag()),
        };
        let numbers: Vec<String> = d.decisive().into_iter().map(|c| c.describe()).collect();
        out.push_str(&format!(
            "| `{}`: {} | {} | {} | {} |\n",
            cell(&v.claim.id),
            cell(&v.claim.words),
            cell(&v.claim.place_and_model()),
            cell(&verdict),
            if numbers.is_empty() {
                "—".to_string()
            } else {
                cell(&numbers.join("; "))
            }
        ));
    }
    for n in &verdicts.not_computable {
        out.push_str(&format!(
            "| `{}`: {} | {} | not decided by code | needs {} |\n",
            cell(&n.id),
            cell(&n.words),
            cell(&n.place),
            cell(&n.needs)
        ));
    }
    out
}
