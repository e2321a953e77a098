//! Every picture states on itself what it shows, and renders alike in PNG and SVG:
//! the heading (figure number, title, the formula variant) is drawn on it, the SVG embeds the
//! font the PNG uses, and no tick reads "-0".

mod common;

use common::{ok_output, scratch_dir};

/// The text of every `<text>` element of an SVG.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

#[test]
fn every_picture_states_what_it_shows() {
    let dir = scratch_dir("pictures");
    let d = dir.to_str().unwrap();
    ok_output(&[
        "figure",
        "all",
        "--quick",
        "--variant",
        "consistent",
        "--out-dir",
        d,
    ]);
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("svg") {
            continue;
        }
        seen += 1;
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let n: u32 = name.trim_start_matches("fig").parse().unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(
            svg.contains("@font-face") && svg.contains("font/ttf;base64,"),
            "{name}: the font is not embedded"
        );
        let texts = svg_texts(&svg);
        assert!(
            texts.iter().any(|t| t.starts_with(&format!("Fig. {n}:"))),
            "{name}: no title"
        );
        if (17..=19).contains(&n) {
            // the Lyapunov figures use the averaged theory only for the starts (its stable
            // amplitudes), and say so there, without the caption's variant line
            let all = texts.join(" ");
            assert!(
                all.contains("stable amplitudes") && all.contains("--variant consistent"),
                "{name}: the outer start's formulas are not stated"
            );
            assert!(
                !texts.iter().any(|t| t.contains("CONSISTENT variant")),
                "{name}: the caption's variant line is back"
            );
        } else {
            assert!(
                texts.iter().any(|t| t.contains("CONSISTENT variant")),
                "{name}: the formula variant is not stated"
            );
        }
        for t in &texts {
            let negative_zero =
                t.starts_with("-0") && t.trim_start_matches(['-', '0', '.']).is_empty();
            assert!(!negative_zero, "{name}: tick label {t:?}");
        }
        let png = std::fs::metadata(path.with_extension("png")).unwrap();
        assert!(png.len() > 10_000, "{name}: PNG of {} bytes", png.len());
    }
    assert_eq!(seen, 19, "pictures written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `width` attribute of an SVG's root element.
fn svg_width(svg: &str) -> f64 {
    let open = &svg[svg.find("<svg").unwrap()..];
    let open = &open[..open.find('>').unwrap()];
    let w = &open[open.find("width=\"").unwrap() + 7..];
    w[..w.find('"').unwrap()].parse().unwrap()
}

/// Every `font-size` attribute of an SVG.
fn svg_font_sizes(svg: &str) -> Vec<f64> {
    svg.split("font-size=\"")
        .skip(1)
        .map(|t| t[..t.find('"').unwrap()].parse().unwrap())
        .collect()
}

/// Printed 7 in (504 pt) wide, no text is smaller than 7 pt: every font size is at least
/// a 72nd of the canvas width, in every figure drawn at the scale of its canvas.
#[test]
fn text_prints_at_seven_points_or_more() {
    let dir = scratch_dir("print_size");
    let d = dir.to_str().unwrap();
    ok_output(&["figure", "all", "--quick", "--out-dir", d]);
    let mut checked = 0;
    for n in 1..=19u32 {
        let path = dir.join(format!("fig{n:02}.svg"));
        let svg = std::fs::read_to_string(&path).unwrap();
        let width = svg_width(&svg);
        let sizes = svg_font_sizes(&svg);
        assert!(
            sizes.len() > 10,
            "fig{n:02}: too few texts ({})",
            sizes.len()
        );
        let min = sizes.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            min >= width / 72.0,
            "fig{n:02}: font-size {min} < width {width} / 72 = {}",
            width / 72.0
        );
        checked += 1;
    }
    assert_eq!(checked, 19);
}

/// Subscripts are drawn as their own, smaller text runs: U_eff's "eff", ΔU_1's "1", D_c's "c".
#[test]
fn subscripts_are_drawn_lowered_and_smaller() {
    let dir = scratch_dir("subscripts");
    let d = dir.to_str().unwrap();
    ok_output(&["figure", "8", "--quick", "--out-dir", d]);
    let svg = std::fs::read_to_string(dir.join("fig08.svg")).unwrap();
    assert!(
        !svg_texts(&svg).iter().any(|t| t.contains("U_eff")),
        "a raw U_eff"
    );
    // the run "eff" follows a run ending in "U", at a smaller size
    let runs: Vec<(f64, String)> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            let size = t.split("font-size=\"").nth(1)?;
            let size: f64 = size[..size.find('"')?].parse().ok()?;
            let body = &t[t.find('>')? + 1..];
            Some((size, body[..body.find("</text>")?].trim().to_string()))
        })
        .collect();
    let found = runs
        .windows(2)
        .any(|w| w[0].1.ends_with('U') && w[1].1 == "eff" && w[1].0 < w[0].0);
    assert!(found, "no U followed by a smaller \"eff\"");
}
