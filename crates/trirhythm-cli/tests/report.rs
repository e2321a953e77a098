//! `trirhythm report`: the page of a real quick run read back (every claim once with a valid
//! verdict, the counts equal to verdicts.json, every picture present, no NaN, every check in
//! checks.json), loaded in a headless Chromium (no console error, every image decoded, a
//! screenshot that is not blank; with the details folded the claims and the rules fit in three
//! screens of 1400 × 900 before the figures; the filters hide the rows they should; the
//! `--single-file` page shows its pictures alone), a figure's data edited so that its verdict
//! flips, and the refusals (an occupied directory, bad flags, an interrupt) leaving nothing
//! behind.

mod common;

use common::{run, scratch_dir};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};
use trirhythm_paper::verdict::claims::{not_computable, registry, FIG04_CLAIMED_ROOTS};

/// One quick report shared by the tests of this file: its directory and its run time.
fn quick_report() -> &'static (PathBuf, Duration) {
    static REPORT: OnceLock<(PathBuf, Duration)> = OnceLock::new();
    REPORT.get_or_init(|| {
        let dir = scratch_dir("report-quick");
        let out = dir.join("report");
        let t = Instant::now();
        let o = run(&["report", "--quick", "--out-dir", out.to_str().unwrap()]);
        let elapsed = t.elapsed();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        (out, elapsed)
    })
}

/// The value of attribute `name` in the start tag `tag` (`<tr a="x" …>`).
fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(tag[start..end].to_string())
}

/// Every start tag `<NAME …>` of `html`, whole.
fn start_tags<'a>(html: &'a str, name: &str) -> Vec<&'a str> {
    let open = format!("<{name} ");
    let mut tags = Vec::new();
    let mut rest = html;
    while let Some(i) = rest.find(&open) {
        let end = rest[i..].find('>').expect("a closed tag") + i + 1;
        tags.push(&rest[i..end]);
        rest = &rest[end..];
    }
    tags
}

/// The text of the element carrying `data-count="KEY"`, as a number.
fn count(html: &str, key: &str) -> usize {
    let marker = format!("data-count=\"{key}\">");
    let i = html.find(&marker).unwrap_or_else(|| panic!("no {marker}")) + marker.len();
    let j = html[i..].find('<').unwrap() + i;
    html[i..j].trim().parse().unwrap()
}

/// `report --from-data data --out-dir out` (which must succeed): its page.
fn report_from(data: &Path, out: &Path) -> String {
    let o = run(&[
        "report",
        "--from-data",
        data.to_str().unwrap(),
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(out.join("index.html")).unwrap()
}

/// (claim id → verdict) of the claims table; panics on a repeated id.
fn rows(html: &str) -> BTreeMap<String, String> {
    let mut map = BTreeMap::new();
    for tag in start_tags(html, "tr") {
        if let Some(id) = attr(tag, "data-claim") {
            let verdict = attr(tag, "data-verdict").expect("a row with a verdict");
            assert!(map.insert(id.clone(), verdict).is_none(), "{id} twice");
        }
    }
    map
}

#[test]
fn quick_report_lists_every_claim_once_with_the_counts_of_its_json() {
    let (out, elapsed) = quick_report();
    // well under a minute (figure all --quick takes seconds)
    assert!(
        elapsed.as_secs_f64() < 45.0,
        "report --quick took {elapsed:?}"
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verdicts.json")).unwrap()).unwrap();
    let rows = rows(&html);
    let expected: BTreeSet<String> = registry()
        .into_iter()
        .map(|c| c.id)
        .chain(not_computable().into_iter().map(|n| n.id))
        .collect();
    assert_eq!(rows.keys().cloned().collect::<BTreeSet<_>>(), expected);
    for (id, v) in &rows {
        assert!(
            ["confirmed", "refuted", "undetermined"].contains(&v.as_str()),
            "{id}: {v}"
        );
    }
    for n in not_computable() {
        assert_eq!(rows[&n.id], "undetermined");
    }
    // every claim of the registry has a rule (issue 34); a row for each claim without one
    assert_eq!(
        html.contains("not decided by code: "),
        !not_computable().is_empty()
    );
    // the page's counts are those of verdicts.json, and of its rows
    let tally = |t: &str| {
        json["claims"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["decision"]["verdict"] == t)
            .count()
    };
    for key in ["confirmed", "refuted", "undetermined"] {
        assert_eq!(
            count(&html, key),
            json["counts"][key].as_u64().unwrap() as usize
        );
        assert_eq!(count(&html, key), tally(key), "{key}");
    }
    assert_eq!(
        count(&html, "not-computable"),
        json["not_computable"].as_array().unwrap().len()
    );
    assert_eq!(count(&html, "not-judged"), 0);
    let rows_of = |t: &str| rows.values().filter(|v| *v == t).count();
    assert_eq!(rows_of("confirmed"), count(&html, "confirmed"));
    assert_eq!(rows_of("refuted"), count(&html, "refuted"));
    assert_eq!(
        rows_of("undetermined"),
        count(&html, "undetermined") + count(&html, "not-computable")
    );
    // each verdict in the JSON is the row's, and the Markdown table's
    let md = std::fs::read_to_string(out.join("claims.md")).unwrap();
    for c in json["claims"].as_array().unwrap() {
        let id = c["claim"]["id"].as_str().unwrap();
        let verdict = c["decision"]["verdict"].as_str().unwrap();
        assert_eq!(rows[id], verdict, "{id}");
        let line = md
            .lines()
            .find(|l| l.starts_with(&format!("| `{id}`")))
            .unwrap_or_else(|| panic!("{id}: no row in claims.md"));
        assert!(line.contains(&format!("**{verdict}**")), "{id}: {line}");
        assert_eq!(line.matches(" | ").count(), 3, "{id}: four cells: {line}");
    }
    assert_eq!(
        md.lines().filter(|l| l.starts_with("| `")).count(),
        expected.len(),
        "one Markdown row per claim"
    );
    // one section per figure, every picture present, linked to its SVG
    let imgs: Vec<String> = start_tags(&html, "img")
        .iter()
        .map(|t| attr(t, "src").unwrap())
        .collect();
    assert_eq!(imgs.len(), 19);
    for (n, src) in (1..=19).zip(&imgs) {
        assert_eq!(src, &format!("figures/fig{n:02}.png"));
        assert!(out.join(src).is_file(), "{src}");
        assert!(html.contains(&format!("id=\"fig-{n:02}\"")));
        assert!(html.contains(&format!("href=\"figures/fig{n:02}.svg\"")));
        assert!(out.join(format!("figures/fig{n:02}.json")).is_file());
        assert!(out.join(format!("figures/fig{n:02}.svg")).is_file());
    }
    for tag in start_tags(&html, "a") {
        let href = attr(tag, "href").unwrap();
        if let Some(anchor) = href.strip_prefix('#') {
            assert!(html.contains(&format!("id=\"{anchor}\"")), "{href}");
        } else {
            assert!(out.join(&href).exists(), "{href}");
        }
    }
    // no NaN, no machine path, the page's frame
    assert!(!html.contains("NaN") && !html.contains(" nan"));
    let root = out.parent().unwrap().to_str().unwrap();
    assert!(!html.contains(root) && !html.contains("/tmp/"));
    assert!(html.starts_with("<!DOCTYPE html>\n<html lang=\"en\">"));
    assert!(html.contains("<meta charset=\"utf-8\">") && html.contains("name=\"viewport\""));
    assert!(html.contains(
        "Managing trirhythmicity and bifurcation in the fractional biological vibro-impact \
         system under correlated noise"
    ));
    // every element the page opens it closes (void elements aside), once per body and html
    for name in [
        "html", "head", "body", "table", "thead", "tbody", "tr", "td", "th", "section", "ul", "li",
        "p", "a", "figure", "span", "code", "h2", "h3", "script", "style", "details", "summary",
        "div", "form", "label", "select", "option",
    ] {
        let opened =
            html.matches(&format!("<{name}>")).count() + html.matches(&format!("<{name} ")).count();
        let closed = html.matches(&format!("</{name}>")).count();
        assert_eq!(
            opened, closed,
            "<{name}> opened {opened} times, closed {closed}"
        );
    }
    assert_eq!(html.matches("<body").count(), 1);
    // the details start folded; each claim's row carries its figure for the filter
    assert!(!html.contains("<details open"));
    for tag in start_tags(&html, "tr") {
        if let (Some(id), Some(fig)) = (attr(tag, "data-claim"), attr(tag, "data-figure")) {
            if let Some(n) = id.strip_prefix("fig").and_then(|r| r.get(..2)) {
                assert_eq!(fig, n.trim_start_matches('0'), "{id}");
            }
        }
    }
    // numbers to significant digits: no binary-float noise such as 0.9844999999999999
    for noise in ["99999999", "00000000"] {
        assert!(!html.contains(noise), "{noise} in the page");
    }
    // verdicts.json keeps at most 50 checks a claim; checks.json has them all
    let checks: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("checks.json")).unwrap()).unwrap();
    let all = checks["claims"].as_array().unwrap();
    let kept = json["claims"].as_array().unwrap();
    assert_eq!(all.len(), kept.len());
    for (a, k) in all.iter().zip(kept) {
        assert_eq!(a["id"], k["claim"]["id"]);
        let (a, k) = (
            a["checks"].as_array().unwrap(),
            k["decision"]["checks"].as_array().unwrap(),
        );
        assert!(k.len() <= 50 && k.len() <= a.len());
        assert!(k.iter().all(|c| a.contains(c)));
        if a.len() <= 50 {
            assert_eq!(a, k);
        }
    }
    assert_eq!(json["report"]["quick"], true);
    assert_eq!(json["report"]["figures"].as_array().unwrap().len(), 19);
    // the report leaves nothing beside itself
    let beside: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(beside, vec![std::ffi::OsString::from("report")]);
}

/// `text` with the entities that the page's templates and the SVG writer use decoded.
fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#x27;", "'")
        .replace("&#39;", "'")
        .replace("&apos;", "'")
        .replace("&#x2f;", "/")
        .replace("&amp;", "&")
}

/// One source of truth: every rendering of a verdict — the verdict line drawn in its figure,
/// its row of claims.md, its row of the page and its entry in verdicts.json — comes from the
/// same decision: the same verdict and the same deciding number (the strongest check's
/// statistic against its threshold, in the words of `Check::statistic_words`); the
/// picture's badge quotes it where it fits, else says "(see caption)", and a figure of more
/// than one verdict counts them on one summary line.
#[test]
fn every_rendering_of_a_verdict_quotes_the_same_deciding_number() {
    use trirhythm_paper::verdict::claims::ClaimVerdict;
    let (out, _) = quick_report();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let md = std::fs::read_to_string(out.join("claims.md")).unwrap();
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verdicts.json")).unwrap()).unwrap();
    let mut svgs = BTreeMap::new();
    for c in json["claims"].as_array().unwrap() {
        let v: ClaimVerdict = serde_json::from_value(c.clone()).expect("a claim verdict");
        let (id, tag) = (&v.claim.id, v.decision.verdict.tag());
        // a decision without checks (a quick figure with nothing to decide from) is
        // undetermined and quotes no number anywhere
        let Some(number) = v.decision.decisive().map(|c| c.statistic_words()) else {
            assert_eq!(tag, "undetermined", "{id}: {tag} without a deciding number");
            continue;
        };
        let line = md
            .lines()
            .find(|l| l.starts_with(&format!("| `{id}`")))
            .unwrap_or_else(|| panic!("{id}: no row in claims.md"));
        assert!(line.contains(&format!("**{tag}**")), "{id}: {line}");
        assert!(
            line.contains(&number),
            "{id}: claims.md lacks {number:?}: {line}"
        );
        let start = html
            .find(&format!("<tr data-claim=\"{id}\""))
            .unwrap_or_else(|| panic!("{id}: no row on the page"));
        let row = unescape(&html[start..start + html[start..].find("</tr>").unwrap()]);
        assert!(row.contains(&format!("data-verdict=\"{tag}\"")), "{id}");
        assert!(
            row.contains(&number),
            "{id}: the page lacks {number:?}: {row}"
        );
        let n = v.claim.figure;
        let svg = svgs.entry(n).or_insert_with(|| {
            unescape(&std::fs::read_to_string(out.join(format!("figures/fig{n:02}.svg"))).unwrap())
        });
        // the picture's badge: one short line, the number where it fits, else "(see
        // caption)"; a figure of more than one verdict draws one summary line
        match svg.lines().find(|l| l.contains(&format!("{id} — "))) {
            Some(drawn) => assert!(
                drawn.contains(&format!("{id} — {tag} ({number}"))
                    || drawn.contains(&format!("{id} — {tag} (see caption)")),
                "{id}: Fig. {n} draws {drawn:?}, claims.md says {tag} ({number})"
            ),
            None => assert!(
                svg.lines()
                    .any(|l| l.contains("verdicts: ") && l.contains(&format!(" {tag}"))),
                "{id}: no verdict line in Fig. {n}, nor a summary counting {tag}"
            ),
        }
    }
}

/// Chromium: `TRIRHYTHM_CHROMIUM`, else `/usr/bin/chromium`.
fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("TRIRHYTHM_CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    path.is_file().then_some(path)
}

/// Run headless Chromium on `url` with `extra` flags; (stdout, stderr).
fn headless(browser: &Path, url: &str, extra: &[&str], scratch: &Path) -> (String, String) {
    let profile = tempdir(scratch, "profile");
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(url)
        .stdin(Stdio::null())
        .output()
        .expect("chromium runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn tempdir(scratch: &Path, name: &str) -> PathBuf {
    let d = scratch.join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_page_loads_in_a_headless_browser() {
    let Some(browser) = chromium() else {
        let why = "no Chromium at /usr/bin/chromium or $TRIRHYTHM_CHROMIUM";
        assert!(
            std::env::var_os("TRIRHYTHM_REQUIRE_BROWSER").is_none(),
            "TRIRHYTHM_REQUIRE_BROWSER is set but {why}"
        );
        eprintln!("skipped: {why}");
        return;
    };
    let (out, _) = quick_report();
    let scratch = scratch_dir("report-browser");
    let url = format!("file://{}", out.join("index.html").display());
    // the DOM after load: the page's script marks whether every image decoded
    let (dom, log) = headless(&browser, &url, &["--dump-dom"], &scratch);
    assert!(
        dom.contains("data-images=\"loaded\"") && dom.contains("data-image-count=\"19\""),
        "images: {}\n{log}",
        dom.lines()
            .find(|l| l.contains("<body"))
            .unwrap_or("no body")
    );
    for line in log.lines() {
        assert!(!line.contains("CONSOLE"), "console message: {line}");
        assert!(
            !line.contains("ERR_FILE_NOT_FOUND") && !line.contains("Failed to load"),
            "{line}"
        );
    }
    // the browser parsed every row
    assert_eq!(
        rows(&dom).len(),
        registry().len() + not_computable().len(),
        "rows in the browser's DOM"
    );
    // a screenshot that is not blank
    let shot = scratch.join("shot.png");
    let (_, log) = headless(
        &browser,
        &url,
        &[
            "--window-size=1200,2400",
            &format!("--screenshot={}", shot.display()),
        ],
        &scratch,
    );
    let file = std::fs::File::open(&shot).unwrap_or_else(|e| panic!("{e}: {log}"));
    let mut decoder = png::Decoder::new(file);
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (1200, 2400));
    let channels = info.color_type.samples();
    assert!(channels >= 3, "{:?}", info.color_type);
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(channels).collect();
    let non_white = pixels.iter().filter(|p| p[..3] != [255, 255, 255]).count();
    let colours: BTreeSet<[u8; 3]> = pixels.iter().map(|p| [p[0], p[1], p[2]]).collect();
    let share = non_white as f64 / pixels.len() as f64;
    assert!(
        share > 0.02,
        "only {share:.4} of the screenshot is not white"
    );
    assert!(colours.len() > 50, "{} distinct colours", colours.len());
    // the verdict colours are drawn (the table's confirmed and refuted cells)
    assert!(colours.contains(&[0xe3, 0xf0, 0xf8]) || colours.contains(&[0xfb, 0xe9, 0xde]));
}

/// The browser, or `None` (with a note) where there is none and none is required.
fn browser_or_skip() -> Option<PathBuf> {
    let browser = chromium();
    if browser.is_none() {
        let why = "no Chromium at /usr/bin/chromium or $TRIRHYTHM_CHROMIUM";
        assert!(
            std::env::var_os("TRIRHYTHM_REQUIRE_BROWSER").is_none(),
            "TRIRHYTHM_REQUIRE_BROWSER is set but {why}"
        );
        eprintln!("skipped: {why}");
    }
    browser
}

#[test]
fn folded_the_page_is_three_screens_before_the_figures() {
    let Some(browser) = browser_or_skip() else {
        return;
    };
    let (out, _) = quick_report();
    let scratch = scratch_dir("report-length");
    // the page as written, with a script that writes on <body> where the figures start
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let measure = "<script>window.addEventListener('load',function(){var f=document.\
        getElementById('figures');document.body.setAttribute('data-figures-at',String(Math.\
        ceil(f.getBoundingClientRect().top+window.scrollY)));document.body.setAttribute(\
        'data-open',String(document.querySelectorAll('details[open]').length));});</script>";
    let page = scratch.join("measured.html");
    std::fs::write(&page, html.replace("</body>", &format!("{measure}</body>"))).unwrap();
    let url = format!("file://{}", page.display());
    let (dom, log) = headless(
        &browser,
        &url,
        &["--window-size=1400,900", "--dump-dom"],
        &scratch,
    );
    let body = start_tags(&dom, "body")[0];
    let at: f64 = attr(body, "data-figures-at")
        .unwrap_or_else(|| panic!("no measure: {body}\n{log}"))
        .parse()
        .unwrap();
    assert_eq!(
        attr(body, "data-open").as_deref(),
        Some("0"),
        "details open"
    );
    eprintln!(
        "the figures start at {at} px: {:.2} screens of 900",
        at / 900.0
    );
    assert!(at <= 3.0 * 900.0, "the figures start at {at} px");
}

#[test]
fn the_filters_hide_the_rows_they_should() {
    let Some(browser) = browser_or_skip() else {
        return;
    };
    let (out, _) = quick_report();
    let scratch = scratch_dir("report-filter");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let all: Vec<(String, String, String)> = start_tags(&html, "tr")
        .iter()
        .filter_map(|t| {
            Some((
                attr(t, "data-claim")?,
                attr(t, "data-verdict")?,
                attr(t, "data-figure")?,
            ))
        })
        .collect();
    assert_eq!(all.len(), registry().len() + not_computable().len());
    let index = out.join("index.html");
    for (verdict, figure) in [("refuted", "4"), ("undetermined", ""), ("", "7")] {
        let mut query = Vec::new();
        if !verdict.is_empty() {
            query.push(format!("verdict={verdict}"));
        }
        if !figure.is_empty() {
            query.push(format!("figure={figure}"));
        }
        let url = format!("file://{}?{}", index.display(), query.join("&"));
        let (dom, log) = headless(&browser, &url, &["--dump-dom"], &scratch);
        let mut shown = BTreeSet::new();
        let mut hidden = BTreeSet::new();
        for tag in start_tags(&dom, "tr") {
            if let Some(id) = attr(tag, "data-claim") {
                if attr(tag, "hidden").is_some() {
                    hidden.insert(id);
                } else {
                    shown.insert(id);
                }
            }
        }
        let expected: BTreeSet<String> = all
            .iter()
            .filter(|(_, v, f)| {
                (verdict.is_empty() || v == verdict) && (figure.is_empty() || f == figure)
            })
            .map(|(id, _, _)| id.clone())
            .collect();
        assert!(!expected.is_empty(), "{query:?} selects nothing");
        assert_eq!(shown, expected, "{query:?}\n{log}");
        assert_eq!(shown.len() + hidden.len(), all.len(), "{query:?}");
        assert!(
            dom.contains(&format!("{} of {} claims shown", expected.len(), all.len())),
            "{query:?}: the status line"
        );
    }
}

#[test]
fn a_single_file_page_shows_its_pictures_alone() {
    let (out, _) = quick_report();
    let scratch = scratch_dir("report-single");
    let single = scratch.join("single");
    let o = run(&[
        "report",
        "--from-data",
        out.join("figures").to_str().unwrap(),
        "--single-file",
        "--out-dir",
        single.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(single.join("index.html")).unwrap();
    let imgs: Vec<String> = start_tags(&html, "img")
        .iter()
        .map(|t| attr(t, "src").unwrap())
        .collect();
    assert_eq!(imgs.len(), 19);
    assert!(imgs.iter().all(|s| s.starts_with("data:image/png;base64,")));
    // no link out of the page
    for tag in start_tags(&html, "a") {
        let href = attr(tag, "href").unwrap();
        assert!(href.starts_with('#'), "{href}");
    }
    assert!(html.contains("--single-file"));
    // the page alone, moved away from its figures/, shows every picture
    let Some(browser) = browser_or_skip() else {
        return;
    };
    let alone = scratch.join("alone");
    std::fs::create_dir_all(&alone).unwrap();
    std::fs::copy(single.join("index.html"), alone.join("page.html")).unwrap();
    let url = format!("file://{}", alone.join("page.html").display());
    let (dom, log) = headless(&browser, &url, &["--dump-dom"], &scratch);
    assert!(
        dom.contains("data-images=\"loaded\"") && dom.contains("data-image-count=\"19\""),
        "{log}"
    );
}

#[test]
fn edited_figure_data_flips_its_verdict() {
    let (out, _) = quick_report();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert_eq!(rows(&html)["fig04-roots"], "refuted");
    let scratch = scratch_dir("report-flip");
    let data = scratch.join("data");
    std::fs::create_dir_all(&data).unwrap();
    let mut fig04: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("figures/fig04.json")).unwrap())
            .unwrap();
    // unedited, Fig. 4 alone: still refuted, the other figures' claims not judged
    std::fs::write(data.join("fig04.json"), fig04.to_string()).unwrap();
    let html = report_from(&data, &scratch.join("before"));
    let r = rows(&html);
    assert_eq!(r["fig04-roots"], "refuted");
    assert_eq!(r["fig07-inner-well"], "undetermined");
    assert!(count(&html, "not-judged") > 20);
    assert!(html.contains("data-missing=\"7\""));
    assert_eq!(start_tags(&html, "img").len(), 1);
    // give each panel the number of roots the paper's text states
    for (panel, n) in fig04["data"]["panels"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .zip(FIG04_CLAIMED_ROOTS)
    {
        panel["cycles"] = Value::Array(
            (0..n)
                .map(|k| {
                    serde_json::json!({"amplitude": 1.0 + k as f64, "stable": k % 2 == 0, "fold": false})
                })
                .collect(),
        );
    }
    std::fs::write(data.join("fig04.json"), fig04.to_string()).unwrap();
    let after = scratch.join("after");
    let html = report_from(&data, &after);
    assert_eq!(rows(&html)["fig04-roots"], "confirmed");
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(after.join("verdicts.json")).unwrap())
            .unwrap();
    assert_eq!(json["report"]["from_data"], true);
    assert_eq!(json["counts"]["confirmed"], 1);
}

#[test]
fn a_report_redraws_from_its_own_figures() {
    let (out, _) = quick_report();
    let scratch = scratch_dir("report-redraw");
    let again = scratch.join("again");
    let figures = out.join("figures");
    report_from(&figures, &again);
    let verdicts = |d: &Path| -> Value {
        let v: Value =
            serde_json::from_str(&std::fs::read_to_string(d.join("verdicts.json")).unwrap())
                .unwrap();
        v["claims"].clone()
    };
    assert_eq!(verdicts(out), verdicts(&again));
    for n in 1..=19 {
        let name = format!("figures/fig{n:02}.png");
        assert_eq!(
            std::fs::read(out.join(&name)).unwrap(),
            std::fs::read(again.join(&name)).unwrap(),
            "{name}"
        );
    }
}

#[test]
fn occupied_directories_and_bad_flags_are_refused_with_nothing_written() {
    let scratch = scratch_dir("report-refusals");
    let listing = |d: &Path| -> BTreeSet<String> {
        std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect()
    };
    // a directory holding something else
    let occupied = scratch.join("occupied");
    std::fs::create_dir_all(&occupied).unwrap();
    std::fs::write(occupied.join("notes.txt"), "mine").unwrap();
    let o = run(&["report", "--quick", "--out-dir", occupied.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--out-dir") && err.contains("notes.txt"),
        "{err}"
    );
    assert_eq!(
        listing(&occupied),
        BTreeSet::from(["notes.txt".to_string()])
    );
    // a file
    let file = scratch.join("file");
    std::fs::write(&file, "x").unwrap();
    let o = run(&["report", "--quick", "--out-dir", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--out-dir"));
    // bad flags: exit 2 naming the flag
    let target = scratch.join("new");
    let t = target.to_str().unwrap();
    for (args, flag) in [
        (
            vec!["report", "--out-dir", t, "--variant", "printed"],
            "--variant",
        ),
        (vec!["report", "--quick"], "--out-dir"),
        (
            vec!["report", "--out-dir", t, "--quick", "--from-data", "x"],
            "--from-data",
        ),
        (
            vec!["report", "--out-dir", t, "--from-data", "no-such-dir"],
            "--from-data",
        ),
        (vec!["report", "--out-dir", t, "--fast"], "--fast"),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(flag), "{args:?}: {err}");
    }
    // from-data of mixed quality
    let mixed = scratch.join("mixed");
    std::fs::create_dir_all(&mixed).unwrap();
    let (out, _) = quick_report();
    std::fs::copy(out.join("figures/fig04.json"), mixed.join("fig04.json")).unwrap();
    let mut full: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("figures/fig07.json")).unwrap())
            .unwrap();
    full["quick"] = Value::Bool(false);
    std::fs::write(mixed.join("fig07.json"), full.to_string()).unwrap();
    let o = run(&[
        "report",
        "--from-data",
        mixed.to_str().unwrap(),
        "--out-dir",
        t,
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("one quality and variant"));
    assert_eq!(
        listing(&scratch),
        BTreeSet::from(["occupied", "file", "mixed"].map(String::from))
    );
    // an empty directory is taken, a previous report replaced
    std::fs::create_dir_all(&target).unwrap();
    let data = scratch.join("mixed");
    std::fs::remove_file(data.join("fig07.json")).unwrap();
    let o = run(&[
        "report",
        "--from-data",
        data.to_str().unwrap(),
        "--out-dir",
        t,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(&[
        "report",
        "--from-data",
        data.to_str().unwrap(),
        "--out-dir",
        t,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        listing(&target),
        BTreeSet::from(
            [
                "index.html",
                "verdicts.json",
                "checks.json",
                "claims.md",
                "figures",
            ]
            .map(String::from)
        )
    );
    assert_eq!(
        listing(&scratch),
        BTreeSet::from(["occupied", "file", "mixed", "new"].map(String::from))
    );
}

#[cfg(unix)]
#[test]
fn an_interrupted_report_leaves_nothing() {
    let scratch = scratch_dir("report-interrupt");
    let out = scratch.join("report");
    // full quality: minutes of work, interrupted once its temporary directory exists
    let child = Command::new(env!("CARGO_BIN_EXE_trirhythm"))
        .args(["report", "--out-dir", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t = Instant::now();
    while std::fs::read_dir(&scratch).unwrap().count() == 0 && t.elapsed() < Duration::from_secs(20)
    {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130));
    let left: Vec<_> = std::fs::read_dir(&scratch)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left {left:?}");
}
