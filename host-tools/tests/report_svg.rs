//! The SVG the report module writes: valid XML, sane structure, no text
//! outside the picture, and no panic or garbage on awkward data.

// Each test crate uses part of the shared gallery.
#[allow(dead_code)]
#[path = "support/gallery.rs"]
mod gallery;

use hyst::report::plots::{loop_overlay, xy, Quantity, Trace};
use hyst::report::{style, Axis, Figure, Panel, Series};
use roxmltree::{Document, Node};

const SVG_NS: &str = "http://www.w3.org/2000/svg";

fn parse(svg: &str) -> Document<'_> {
    Document::parse(svg).unwrap_or_else(|e| panic!("not well-formed XML: {e}\n{svg}"))
}

fn class<'a>(doc: &'a Document, name: &str) -> Vec<Node<'a, 'a>> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(name))
        .collect()
}

fn texts(doc: &Document, name: &str) -> Vec<String> {
    class(doc, name)
        .iter()
        .map(|n| n.text().unwrap_or("").to_string())
        .collect()
}

/// Every number in path data and positions is finite, and every
/// unrotated text lies inside the picture (estimated with the same width
/// model the layout uses).
fn assert_sane(svg: &str) {
    let doc = parse(svg);
    let root = doc.root_element();
    assert_eq!(root.tag_name().namespace(), Some(SVG_NS));
    let w: f64 = root.attribute("width").unwrap().parse().unwrap();
    let h: f64 = root.attribute("height").unwrap().parse().unwrap();
    for n in doc.descendants().filter(|n| n.is_element()) {
        for a in n.attributes() {
            let v = a.value().to_ascii_lowercase();
            assert!(
                !v.contains("nan") && !v.contains("inf"),
                "non-finite number in {}={}",
                a.name(),
                a.value()
            );
        }
        if n.tag_name().name() != "text" || n.attribute("transform").is_some() {
            continue;
        }
        let x: f64 = n.attribute("x").unwrap().parse().unwrap();
        let y: f64 = n.attribute("y").unwrap().parse().unwrap();
        let size: f64 = n
            .attribute("font-size")
            .map_or(style::FONT_SMALL, |s| s.parse().unwrap());
        let text = n.text().unwrap_or("");
        let width = style::text_width(text, size);
        let x0 = match n.attribute("text-anchor") {
            Some("middle") => x - width / 2.0,
            Some("end") => x - width,
            _ => x,
        };
        assert!(
            x0 >= -0.5 && x0 + width <= w + 0.5 && y - 0.8 * size >= -0.5 && y <= h + 0.5,
            "text '{text}' at ({x0:.0}..{:.0}, {y:.0}) sticks out of {w}x{h}",
            x0 + width
        );
    }
}

#[test]
fn every_gallery_figure_is_valid_svg_with_text_inside() {
    let figures = gallery::figures();
    assert_eq!(figures.len(), 9, "one figure per plot kind");
    for (id, fig, _) in figures {
        let svg = fig.to_svg();
        assert!(svg.starts_with("<?xml"), "{id}");
        assert_sane(&svg);
        let doc = parse(&svg);
        assert!(class(&doc, "tick").len() >= 4, "{id}: too few tick labels");
        assert!(
            !class(&doc, "axis-label").is_empty(),
            "{id}: no axis labels"
        );
    }
}

#[test]
fn loop_overlay_structure() {
    let u: Vec<f64> = (0..100).map(|i| (i as f64 / 10.0).sin() * 5.0).collect();
    let f: Vec<f64> = u.iter().map(|u| 3.0 * u).collect();
    let g: Vec<f64> = u.iter().map(|u| 2.9 * u).collect();
    let fig = loop_overlay(
        &[
            Trace::measured("measured", &u, &f),
            Trace::model("bw", &u, &g),
            Trace::model("bwbn", &u, &g),
        ],
        Quantity::new("Displacement", "mm"),
        Quantity::new("Force", "kN"),
    )
    .unwrap();
    let svg = fig.to_svg();
    let doc = parse(&svg);
    let lines = class(&doc, "line");
    assert_eq!(lines.len(), 3);
    let names: Vec<&str> = lines
        .iter()
        .map(|n| n.attribute("data-name").unwrap())
        .collect();
    assert_eq!(names, ["measured", "bw", "bwbn"]);
    let colours: Vec<&str> = lines
        .iter()
        .map(|n| n.attribute("stroke").unwrap())
        .collect();
    assert_eq!(colours, ["#8c8c8c", "#0072b2", "#d55e00"]);
    assert_eq!(
        texts(&doc, "axis-label"),
        ["Displacement (mm)", "Force (kN)"]
    );
    let legend = class(&doc, "legend");
    assert_eq!(legend.len(), 1);
    let entries: Vec<&str> = legend[0]
        .children()
        .filter(|n| n.tag_name().name() == "text")
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(entries, ["measured", "bw", "bwbn"]);
    // Ticks: −4 … 4 on x and −15 … 15 on y, with true minus signs.
    let ticks = texts(&doc, "tick");
    assert!(ticks.contains(&"\u{2212}4".to_string()), "{ticks:?}");
    assert!(ticks.contains(&"10".to_string()), "{ticks:?}");
    // Exactly one clip path, used by the data group.
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name((SVG_NS, "clipPath")))
            .count(),
        1
    );
}

/// Plots `y` against its index with a linear or log y axis.
fn plot(y: &[f64], axis: Axis) -> String {
    let x: Vec<f64> = (0..y.len()).map(|i| i as f64).collect();
    let mut p = Panel::new(Axis::linear("Sample", ""), axis);
    p.series(Series::line("signal", &x, y).unwrap());
    let mut f = Figure::new(500.0, 300.0);
    f.panel(p);
    f.to_svg()
}

fn y_ticks(svg: &str) -> Vec<String> {
    let doc = parse(svg);
    class(&doc, "tick")
        .iter()
        .filter(|n| n.attribute("text-anchor") == Some("end"))
        .map(|n| n.text().unwrap().to_string())
        .collect()
}

fn notes(svg: &str) -> Vec<String> {
    texts(&parse(svg), "note")
}

#[test]
fn tiny_values_get_an_engineering_exponent() {
    let svg = plot(&[1e-9, 3e-9, 2e-9, 4.5e-9], Axis::linear("Drift", "m"));
    assert_sane(&svg);
    assert!(svg.contains(">Drift (×10⁻⁹ m)<"), "{svg}");
    let t = y_ticks(&svg);
    assert!(t.len() >= 3 && t.iter().all(|l| l.len() <= 3), "{t:?}");
}

#[test]
fn huge_values_get_an_engineering_exponent() {
    let svg = plot(&[2.0e9, 7.5e9, -1.0e9], Axis::linear("Stiffness", "N/m"));
    assert_sane(&svg);
    assert!(svg.contains(">Stiffness (×10⁹ N/m)<"), "{svg}");
}

#[test]
fn negative_only_values() {
    let svg = plot(&[-120.0, -80.0, -95.0], Axis::linear("Force", "kN"));
    assert_sane(&svg);
    let t = y_ticks(&svg);
    assert!(t.iter().all(|l| l.starts_with('\u{2212}')), "{t:?}");
}

#[test]
fn constant_signal_gets_a_range_around_it() {
    for v in [0.0, 42.0, -3e-7] {
        let svg = plot(&[v; 10], Axis::linear("Force", "kN"));
        assert_sane(&svg);
        assert!(y_ticks(&svg).len() >= 2, "{v}: {svg}");
        assert!(notes(&svg).is_empty());
    }
}

#[test]
fn nan_values_are_skipped_with_a_visible_note() {
    let svg = plot(
        &[1.0, f64::NAN, 3.0, f64::INFINITY, 2.0],
        Axis::linear("Force", "kN"),
    );
    assert_sane(&svg);
    assert_eq!(
        notes(&svg),
        ["Note: 2 points with NaN or infinite values of 'signal' not drawn."]
    );
    // The line breaks at the gaps: three pieces, three move-to commands.
    let doc = parse(&svg);
    let d = class(&doc, "line")[0].attribute("d").unwrap().to_string();
    assert_eq!(d.matches('M').count(), 3, "{d}");
}

#[test]
fn all_nan_data_says_so() {
    let svg = plot(&[f64::NAN; 4], Axis::linear("Force", "kN"));
    assert_sane(&svg);
    let n = notes(&svg);
    assert!(n.iter().any(|s| s.contains("4 points with NaN")), "{n:?}");
    assert!(n.iter().any(|s| s.contains("No data to show")), "{n:?}");
    assert!(class(&parse(&svg), "line").is_empty());
}

#[test]
fn log_axis_skips_non_positive_values_with_a_note() {
    let svg = plot(&[0.3, 0.0, 0.1, -1.0, 0.02], Axis::log("NRMSE", ""));
    assert_sane(&svg);
    assert_eq!(
        notes(&svg),
        ["Note: 2 points of 'signal' at or below zero not drawn on the log axis."]
    );
    assert_eq!(y_ticks(&svg), ["0.02", "0.05", "0.1", "0.2"]);
}

#[test]
fn empty_and_degenerate_figures_do_not_panic() {
    assert_sane(&Figure::new(300.0, 200.0).to_svg());
    let fig = xy(
        "Nothing",
        Quantity::new("x", ""),
        Quantity::new("y", ""),
        &[],
    )
    .unwrap();
    let svg = fig.to_svg();
    assert_sane(&svg);
    assert!(notes(&svg).iter().any(|n| n.contains("No data")));
    // A figure far too small for its panel still renders.
    let mut tiny = Figure::new(10.0, 10.0);
    tiny.panel(Panel::new(Axis::linear("x", ""), Axis::linear("y", "")));
    parse(&tiny.to_svg());
}

#[test]
fn report_page_figures_are_well_formed_and_ids_unique() {
    let html = gallery::report().to_html();
    let mut ids = std::collections::HashSet::new();
    let mut figures = 0;
    for chunk in html.split("<svg ").skip(1) {
        let end = chunk.find("</svg>").expect("closed svg") + "</svg>".len();
        // Inline SVG has no namespace; give it one to read it as XML.
        let svg = format!("<svg xmlns=\"{SVG_NS}\" {}", &chunk[..end]);
        let doc = parse(&svg);
        for id in doc.descendants().filter_map(|n| n.attribute("id")) {
            assert!(ids.insert(id.to_string()), "duplicate id {id}");
        }
        figures += 1;
    }
    assert_eq!(figures, 9);
}

#[test]
fn inline_form_has_no_namespace_and_prefixed_ids() {
    let (_, fig, _) = gallery::figures().remove(0);
    let inline = fig.to_svg_inline("f7 <x>");
    assert!(inline.starts_with("<svg "));
    assert!(!inline.contains("xmlns"));
    assert!(inline.contains("id=\"f7x-p0-clip\""));
    assert!(inline.contains("url(#f7x-p0-clip)"));
}

#[test]
fn long_titles_and_names_are_shortened_not_clipped() {
    let long = "A very long panel title that cannot possibly fit into a narrow figure at all";
    let mut p = Panel::new(Axis::linear(long, "mm"), Axis::linear(long, "kN"));
    p.title(long);
    p.series(Series::line(long, &[0.0, 1.0], &[0.0, 1.0]).unwrap());
    let mut f = Figure::new(260.0, 220.0);
    f.title(long);
    f.panel(p);
    let svg = f.to_svg();
    assert_sane(&svg);
    let doc = parse(&svg);
    let shortened: Vec<Node> = doc
        .descendants()
        .filter(|n| n.has_tag_name((SVG_NS, "text")) && n.text().is_some_and(|t| t.ends_with('…')))
        .collect();
    // Figure title, panel title, both axis titles and the legend entry.
    assert_eq!(shortened.len(), 5, "{svg}");
    for n in shortened {
        let full = n.children().find(|c| c.has_tag_name((SVG_NS, "title")));
        assert!(full
            .and_then(|t| t.text())
            .is_some_and(|t| t.starts_with(long)));
    }
}

#[test]
fn many_cycles_thin_their_labels_and_long_names_rotate() {
    use hyst::report::plots::{ladder, per_cycle_bars, Rung, Signal};
    let e: Vec<f64> = (0..120).map(|c| 10.0 + c as f64).collect();
    let svg = per_cycle_bars(
        Quantity::new("Energy", "kN·mm"),
        &[Signal::measured("measured", "kN·mm", &e)],
    )
    .unwrap()
    .to_svg();
    assert_sane(&svg);
    // Cycle numbers thinned to 1, 10, 20, … 120, level.
    let doc = parse(&svg);
    let cycles: Vec<String> = class(&doc, "tick")
        .iter()
        .filter(|n| n.attribute("text-anchor") == Some("middle"))
        .map(|n| n.text().unwrap().to_string())
        .collect();
    let expected: Vec<String> = std::iter::once(1)
        .chain((10..=120).step_by(10))
        .map(|c| c.to_string())
        .collect();
    assert_eq!(cycles, expected);

    let names = [
        "bw",
        "+strength-degradation",
        "+stiffness-degradation",
        "+pinching",
        "+asymmetry",
        "+rate-dependence",
    ];
    let rungs: Vec<Rung> = names
        .iter()
        .enumerate()
        .map(|(i, n)| Rung {
            label: n,
            params: 5 + 2 * i,
            nrmse: 0.3 / (i as f64 + 1.0),
            delta_bic: (i > 0).then_some(-100.0 / i as f64),
        })
        .collect();
    let svg = ladder(&rungs, None).unwrap().to_svg();
    assert_sane(&svg);
    let doc = parse(&svg);
    let rotated = class(&doc, "tick")
        .iter()
        .filter(|n| {
            n.attribute("transform")
                .is_some_and(|t| t.starts_with("rotate"))
        })
        .count();
    assert_eq!(
        rotated,
        2 * names.len(),
        "every rung named, slanted, in both panels"
    );
}
