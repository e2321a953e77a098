//! `trirhythm report`: every figure computed (or read from figure data), every claim of the
//! paper judged, and one HTML page with the verdicts, the figures and the provenance (linking
//! the pictures in `figures/`, or holding them with `--single-file`).
//!
//! Method: the figures are made one after the other by the same code as `trirhythm figure`
//! ([`crate::render::paper`]), each collected in a `Figures` value; the claims are judged at once
//! by `trirhythm_paper::verdict::claims::judge`; the page is [`crate::render::report::page`].
//! Everything is built in a hidden sibling of `--out-dir` and renamed onto it at the end: an
//! error or an interrupt leaves no partial report. The destination is checked before any work
//! (new, empty, or a previous report whose every file its `verdicts.json` lists; writable) and
//! again at the end: a file that is not a report's own, there at the start or added during
//! the run, is never replaced or deleted ([`report_entries`]). Tested by `tests/report.rs` and
//! `tests/hostile.rs`.

use crate::args::{Named, VariantArg};
use crate::error::bad;
use crate::io::files::{probe_dir, OwnEntries};
use crate::io::{stdout_write, write_atomic, TemporaryDir};
use crate::render::claims_table::claims_markdown;
use crate::render::paper::{data_options, registry, Request};
use crate::render::report::{
    page, summarised, ChecksFile, Counts, FigureRun, Page, Provenance, Section, VerdictsFile,
};
use anyhow::{Context, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::Instant;
use trirhythm_paper::verdict::claims::{judge, Figures};
use trirhythm_paper::FigureOptions;

/// The entries a report directory holds.
const REPORT_ENTRIES: [&str; 5] = [
    "index.html",
    "verdicts.json",
    "checks.json",
    "claims.md",
    "figures",
];

#[derive(Debug, clap::Args)]
#[command(
    after_help = "Files, in --out-dir: index.html (the page: the counts, the claims table — one \
    line per claim with its verdict and deciding number, filters by verdict and figure, the \
    details of each claim folded in its row —, the rules, the paper, one section per figure, \
    the provenance; it links the pictures in figures/, or holds them with --single-file), \
    verdicts.json (the verdicts as data, with the counts and the provenance; at most 50 checks \
    a claim), checks.json (every check of every claim), claims.md (the claims table in Markdown) and figures/ (each figure's CSV, PNG, SVG and figNN.json, so that `report --from-data \
    DIR/figures` draws the report again without computing).\n\
    The report is built in a hidden sibling directory and renamed onto --out-dir when \
    complete. --out-dir must not exist, be empty, or hold a previous report (index.html, \
    verdicts.json, checks.json, claims.md, figures/ with the files its verdicts.json lists, and nothing \
    else), which is replaced; it is checked again before the replacement, and a file the \
    report did not write, there or added during the run, is never replaced or deleted (exit 2, \
    the folder left as it was)."
)]
pub struct ReportArgs {
    /// Directory of the report (created; a previous report there is replaced).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Coarser grids and shorter runs (for CI and previews).
    #[arg(long)]
    pub quick: bool,
    /// Formula variant of the averaged theory.
    #[arg(long, value_enum, default_value_t = VariantArg::Paper)]
    pub variant: VariantArg,
    /// Read the figures from DIR/figNN.json (written by `figure --data` or a previous report's
    /// figures/) instead of computing; a missing figure is reported as not in the data.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["quick", "variant"])]
    pub from_data: Option<PathBuf>,
    /// Put the pictures inside index.html (PNG as data: URIs), so that the page alone shows
    /// everything; the data files stay in figures/, named but not linked.
    #[arg(long)]
    pub single_file: bool,
    /// Print each figure's parallel profile to stderr (as `figure --profile`).
    #[arg(long, conflicts_with = "from_data")]
    pub profile: bool,
}

/// `report`: compute or read every figure, judge every claim, write the page.
pub fn report(args: &ReportArgs) -> Result<()> {
    let start = Instant::now();
    check_out_dir(&args.out_dir)?;
    // with --from-data, the figures present in the data (each read once here)
    let (options, request, present) = match &args.from_data {
        None => {
            let options = FigureOptions {
                quick: args.quick,
                variant: args.variant.into(),
            };
            let request = Request::Compute {
                options,
                profile: args.profile,
            };
            (options, request, None)
        }
        Some(dir) => {
            let (options, present) = data_dir_options(dir)?;
            (options, Request::FromData(dir.as_path()), Some(present))
        }
    };
    let tmp = TemporaryDir::create(&args.out_dir).or_else(|e| {
        bad(format!(
            "--out-dir {}: cannot write beside it ({e:#})",
            args.out_dir.display()
        ))
    })?;
    let figures_dir = tmp.path().join("figures");
    let mut figures = Figures {
        options,
        ..Default::default()
    };
    let mut sections = Vec::new();
    let mut runs = Vec::new();
    for entry in registry() {
        let t = Instant::now();
        let missing = present.as_ref().is_some_and(|p| !p.contains(&entry.number));
        if missing {
            sections.push(Section {
                number: entry.number,
                title: entry.title.into(),
                heading: None,
            });
            runs.push(FigureRun {
                figure: entry.number,
                status: "not in the data".into(),
                seconds: 0.0,
                files: vec![],
            });
            continue;
        }
        let made = (entry.make)(&request, &figures_dir, true, Some(&mut figures))?;
        let seconds = t.elapsed().as_secs_f64();
        eprintln!("figure {} ({}): {seconds:.1} s", entry.number, entry.title);
        if let Some(p) = &made.profile {
            eprintln!("figure {} profile: {}", entry.number, p.line());
        }
        let files = made
            .files
            .iter()
            .filter_map(|f| f.file_name())
            .map(|n| format!("figures/{}", n.to_string_lossy()))
            .collect();
        sections.push(Section {
            number: entry.number,
            title: entry.title.into(),
            heading: Some(made.heading),
        });
        runs.push(FigureRun {
            figure: entry.number,
            status: if args.from_data.is_some() {
                "read".into()
            } else {
                "computed".into()
            },
            seconds,
            files,
        });
    }
    let verdicts = judge(&figures);
    let provenance = Provenance {
        trirhythm: env!("CARGO_PKG_VERSION").into(),
        commit: option_env!("TRIRHYTHM_COMMIT").unwrap_or("unknown").into(),
        quick: options.quick,
        variant: VariantArg::from(options.variant).name(),
        from_data: args.from_data.is_some(),
        command: command_line(args),
        figures: runs,
        total_seconds: start.elapsed().as_secs_f64(),
    };
    let counts = Counts::of(&verdicts);
    let json = serde_json::to_string_pretty(&VerdictsFile {
        report: &provenance,
        counts,
        verdicts: &summarised(&verdicts),
    })
    .context("serialising the verdicts")?;
    write_atomic(&tmp.path().join("verdicts.json"), json.as_bytes())?;
    let checks = serde_json::to_string(&ChecksFile::of(&verdicts, &provenance))
        .context("serialising the checks")?;
    write_atomic(&tmp.path().join("checks.json"), checks.as_bytes())?;
    let html = page(&Page {
        verdicts: &verdicts,
        sections: &sections,
        provenance: &provenance,
        inline_from: args.single_file.then_some(figures_dir.as_path()),
    })?;
    write_atomic(&tmp.path().join("index.html"), html.as_bytes())?;
    let source = format!(
        "trirhythm {}, commit {}, {} quality, {} variant",
        provenance.trirhythm,
        provenance.commit,
        if provenance.quick { "quick" } else { "full" },
        provenance.variant
    );
    write_atomic(
        &tmp.path().join("claims.md"),
        claims_markdown(&verdicts, &source).as_bytes(),
    )?;
    // the destination checked again: it may have changed while the report was computed
    tmp.commit_replacing("--out-dir", &report_entries)?;
    eprintln!(
        "report: {} confirmed, {} refuted, {} undetermined ({} not decided by code, {} not \
         judged) in {:.1} s",
        counts.confirmed,
        counts.refuted,
        counts.undetermined,
        counts.not_computable,
        counts.not_judged,
        start.elapsed().as_secs_f64()
    );
    let index = args.out_dir.join("index.html");
    stdout_write(format!("{}\n", index.display()).as_bytes())
}

/// Refuse an `--out-dir` the report may not take: a file, a path without a name (`.`, `/`), a
/// directory in a missing or unwritable parent, a non-empty directory that is not wholly a
/// previous report ([`report_entries`]), or a previous report whose files cannot be removed.
fn check_out_dir(dir: &Path) -> Result<()> {
    let shown = dir.display();
    let named = dir.file_name().is_some_and(|n| n != "." && n != "..");
    if !named {
        return bad(format!(
            "--out-dir {shown}: not a directory name the report can be renamed onto; give a \
             new directory such as `report`"
        ));
    }
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return bad(format!(
            "--out-dir {shown}: directory {} does not exist",
            parent.display()
        ));
    }
    if let Err(e) = probe_dir(parent) {
        return bad(format!(
            "--out-dir {shown}: cannot write in its directory {} ({e})",
            parent.display()
        ));
    }
    let Ok(meta) = std::fs::symlink_metadata(dir) else {
        return Ok(());
    };
    if !meta.is_dir() {
        return bad(format!(
            "--out-dir {shown}: exists and is not a directory; give a new directory"
        ));
    }
    let entries = match report_entries(dir) {
        Ok(e) => e,
        Err(foreign) => {
            return bad(format!(
                "--out-dir {shown}: exists and is neither empty nor a previous report (it \
                 holds {foreign}); give a new or empty directory (a previous report — \
                 index.html, verdicts.json, checks.json, claims.md, figures/ with the files its \
                 verdicts.json lists, and nothing else — is replaced)"
            ))
        }
    };
    // a previous report is replaced: its files must be removable
    if !entries.is_empty() {
        for d in [dir.to_path_buf(), dir.join("figures")] {
            if d.is_dir() {
                if let Err(e) = probe_dir(&d) {
                    return bad(format!(
                        "--out-dir {shown}: the previous report there cannot be replaced: {} \
                         takes no change ({e})",
                        d.display()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// What a report directory holds when all of it is a report's own: `index.html`,
/// `verdicts.json` (a report's: [`is_report_value`]), `checks.json`, `claims.md`, and in `figures/` only the files
/// that `verdicts.json` lists as written (`report.figures[].files`), all regular files — the
/// paths relative to `dir` in the order they are removed (files, then `figures`); empty for an
/// empty directory. Otherwise the first entry that is not the report's, in words.
fn report_entries(dir: &Path) -> OwnEntries {
    let names = |d: &Path| -> std::result::Result<Vec<String>, String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .map_err(|e| format!("{} (unreadable: {e})", d.display()))?
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        Ok(v)
    };
    let top = names(dir)?;
    if top.is_empty() {
        return Ok(vec![]);
    }
    if let Some(f) = top.iter().find(|e| !REPORT_ENTRIES.contains(&e.as_str())) {
        return Err(f.clone());
    }
    let Some(listed) = report_files(&dir.join("verdicts.json")) else {
        return Err(format!(
            "{} without a report's verdicts.json",
            top.iter()
                .find(|e| *e != "verdicts.json")
                .cloned()
                .unwrap_or_else(|| "verdicts.json".into())
        ));
    };
    let is_file = |p: &Path| std::fs::symlink_metadata(p).is_ok_and(|m| m.is_file());
    let is_dir = |p: &Path| std::fs::symlink_metadata(p).is_ok_and(|m| m.is_dir());
    let mut own = Vec::new();
    if top.iter().any(|e| e == "figures") {
        let figures = dir.join("figures");
        if !is_dir(&figures) {
            return Err("figures (not a directory)".into());
        }
        for f in names(&figures)? {
            let rel = format!("figures/{f}");
            if !listed.contains(&rel) || !is_file(&dir.join(&rel)) {
                return Err(rel);
            }
            own.push(PathBuf::from(rel));
        }
    }
    for f in top.iter().filter(|e| *e != "figures") {
        if !is_file(&dir.join(f)) {
            return Err(format!("{f} (not a file)"));
        }
        own.push(PathBuf::from(f));
    }
    if top.iter().any(|e| e == "figures") {
        own.push(PathBuf::from("figures"));
    }
    Ok(own)
}

/// The figure files a report's `verdicts.json` lists as written (`figures/NAME`), if it is a
/// report's ([`is_report_value`]).
fn report_files(path: &Path) -> Option<BTreeSet<String>> {
    let text = std::fs::read_to_string(path).ok()?;
    let value = serde_json::from_str::<serde_json::Value>(&text).ok()?;
    if !is_report_value(&value) {
        return None;
    }
    let figures = value.get("report")?.get("figures")?.as_array()?;
    Some(
        figures
            .iter()
            .filter_map(|f| f.get("files").and_then(|f| f.as_array()))
            .flatten()
            .filter_map(|f| f.as_str())
            .filter(|f| f.starts_with("figures/") && !f[8..].contains(['/', '\\']))
            .map(str::to_string)
            .collect(),
    )
}

/// Whether a parsed `verdicts.json` is a report's (an object with a `report` object naming
/// the trirhythm version).
fn is_report_value(value: &serde_json::Value) -> bool {
    value
        .get("report")
        .and_then(|r| r.get("trirhythm"))
        .is_some_and(|v| v.is_string())
}

/// The options of the figure data in `dir`, and the figures it holds: every `figNN.json` there
/// must share them; at least one must exist.
fn data_dir_options(dir: &Path) -> Result<(FigureOptions, BTreeSet<u32>)> {
    if !dir.is_dir() {
        return bad(format!(
            "--from-data {}: not a directory (give the directory holding figNN.json, e.g. a \
             previous report's figures/)",
            dir.display()
        ));
    }
    let mut found: Vec<(u32, FigureOptions)> = Vec::new();
    for entry in registry() {
        if let Some(o) = data_options(dir, entry.number)? {
            found.push((entry.number, o));
        }
    }
    let Some(&(first, options)) = found.first() else {
        return bad(format!(
            "--from-data {}: holds no figure data (figNN.json); write it with `figure all \
             --data` or `report`",
            dir.display()
        ));
    };
    if let Some((n, o)) = found.iter().find(|(_, o)| *o != options) {
        let describe = |o: &FigureOptions| {
            format!(
                "{}, {} variant",
                if o.quick { "quick" } else { "full" },
                VariantArg::from(o.variant).name()
            )
        };
        return bad(format!(
            "--from-data {}: figure {first} was computed {} but figure {n} {}; a report is \
             judged from figures of one quality and variant",
            dir.display(),
            describe(&options),
            describe(o)
        ));
    }
    Ok((options, found.iter().map(|(n, _)| *n).collect()))
}

/// The command line as typed, with each path as a name relative to the report (no absolute
/// path of the machine).
fn command_line(args: &ReportArgs) -> String {
    let name = |p: &Path| -> String {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "DIR".into())
    };
    let out = name(&args.out_dir);
    let mut line = format!("trirhythm report --out-dir {out}");
    match &args.from_data {
        None => {
            if args.quick {
                line.push_str(" --quick");
            }
            line.push_str(&format!(" --variant {}", args.variant.name()));
        }
        Some(dir) => {
            let inside = match (dir.canonicalize(), args.out_dir.canonicalize()) {
                (Ok(d), Ok(o)) => d
                    .strip_prefix(&o)
                    .ok()
                    .map(|rest| PathBuf::from(&out).join(rest)),
                _ => None,
            };
            let shown = inside
                .map(|p| p.display().to_string())
                .unwrap_or_else(|| name(dir));
            line.push_str(&format!(" --from-data {shown}"));
        }
    }
    if args.single_file {
        line.push_str(" --single-file");
    }
    line
}
