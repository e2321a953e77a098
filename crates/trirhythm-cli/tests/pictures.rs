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
            // the Lyapunov figures use the averaged theory only for the outer start, and say
            // so there, without the caption's variant line
            let all = texts.join(" ");
            assert!(
                all.contains("outer stable cycle") && all.contains("--variant consistent"),
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
