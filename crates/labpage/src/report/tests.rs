use super::*;
use crate::clock::Clock;
use crate::experiment::{
    Experiment, Input, Lab, ParamError, Presentation, Readout, Sanitized, Status,
};
use crate::plot::{Band, Marker, RefLine};
use crate::scene::{Scene, ViewBox};

/// Every report in these tests is made as the page makes it: the
/// experiment's module writes the [`Sheet`] as bytes, the report module reads
/// them back and renders. Reading back and writing again gives the same
/// bytes (floats cross as their bits, so NaN and −0 survive too).
fn render(r: &Report<'_>) -> String {
    let bytes = wire::encode(&Sheet::of(r));
    let sheet: Sheet = wire::decode(&bytes).expect("the sheet reads back");
    assert_eq!(
        wire::encode(&sheet),
        bytes,
        "the sheet reads back as written"
    );
    let html = render_bytes(&bytes).expect("the report module renders it");
    assert_eq!(
        html,
        super::render(r),
        "the same report as made in one piece"
    );
    html
}

/// A damaged sheet gives an error, never a panic: cut short anywhere, or
/// with any one byte changed.
#[test]
fn a_damaged_report_sheet_is_an_error_not_a_panic() {
    let (html, ..) = quiz_report("pid", 7, true, AnswerKey::Submitted, Student::default());
    assert!(html.contains("Self-assessment"));
    let entry = crate::find("cartpole").unwrap();
    let mut exp = (entry.make)();
    for _ in 0..120 {
        exp.step(Clock::DT_S);
    }
    let content = entry.content().unwrap();
    let bytes = wire::encode(&Sheet::of(&Report {
        experiment: exp.as_ref(),
        content,
        link: "http://localhost/#/cartpole/simulation",
        date: "today",
        quiz: None,
        note: Some("note"),
        student: Student::default(),
        answer_key: AnswerKey::Never,
        marks: &[],
        shown: None,
    }));
    for cut in 0..bytes.len() {
        assert!(
            render_bytes(&bytes[..cut]).is_err(),
            "cut at {cut} of {}",
            bytes.len()
        );
    }
    let mut extra = bytes.clone();
    extra.push(0);
    assert!(render_bytes(&extra).is_err(), "a byte left over");
    // Every byte changed to 0xff: whatever it reads as, nothing panics.
    for i in (0..bytes.len()).step_by(7) {
        let mut damaged = bytes.clone();
        damaged[i] = 0xff;
        let _ = render_bytes(&damaged);
    }
}

/// Checks that every tag of `html` is closed in order (HTML void elements
/// and `/>` excepted), skipping the doctype and the style sheet; returns the
/// problem found. Quote-aware, so a `>` inside an attribute value is fine.
fn balanced(html: &str) -> Result<(), String> {
    const VOID: [&str; 8] = ["meta", "br", "hr", "img", "input", "link", "col", "wbr"];
    let mut stack: Vec<String> = Vec::new();
    let b = html.as_bytes();
    let mut i = 0;
    while let Some(off) = html[i..].find('<') {
        let start = i + off;
        if html[start..].starts_with("<!") {
            i = start + html[start..].find('>').ok_or("unclosed doctype")? + 1;
            continue;
        }
        // Find the end of the tag, outside quotes.
        let mut j = start + 1;
        let mut quote: Option<u8> = None;
        while j < b.len() {
            match (quote, b[j]) {
                (None, b'"' | b'\'') => quote = Some(b[j]),
                (Some(q), c) if c == q => quote = None,
                (None, b'>') => break,
                _ => {}
            }
            j += 1;
        }
        if j >= b.len() {
            return Err(format!("unterminated tag at {start}"));
        }
        let tag = &html[start + 1..j];
        i = j + 1;
        if let Some(name) = tag.strip_prefix('/') {
            let name = name.trim();
            match stack.pop() {
                Some(open) if open == name => {}
                other => return Err(format!("</{name}> closes {other:?} at {start}")),
            }
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| !c.is_whitespace() && *c != '/')
            .collect();
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric()) {
            return Err(format!("odd tag <{tag}> at {start}"));
        }
        if tag.ends_with('/') || VOID.contains(&name.as_str()) {
            continue;
        }
        if name == "style" {
            let end = html[i..].find("</style>").ok_or("unclosed style")?;
            i += end + "</style>".len();
            continue;
        }
        stack.push(name);
    }
    if stack.is_empty() {
        Ok(())
    } else {
        Err(format!("unclosed: {stack:?}"))
    }
}

/// Each `<svg>…</svg>` of the page: balanced with no void elements (every
/// empty element self-closed, as XML wants) and only XML's entities.
fn svgs(html: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = html;
    while let Some(a) = rest.find("<svg") {
        let end = rest[a..].find("</svg>").expect("svg closed") + a + "</svg>".len();
        out.push(&rest[a..end]);
        rest = &rest[end..];
    }
    out
}

fn well_formed_svg(svg: &str) -> Result<(), String> {
    balanced(svg)?;
    for void in ["<br", "<meta", "<img", "<input"] {
        if svg.contains(void) {
            return Err(format!("{void} in svg"));
        }
    }
    for (k, _) in svg.match_indices('&') {
        let tail = &svg[k..];
        if !["&amp;", "&lt;", "&gt;", "&quot;", "&#39;"]
            .iter()
            .any(|e| tail.starts_with(e))
        {
            return Err(format!("entity {}", &tail[..tail.len().min(8)]));
        }
    }
    Ok(())
}

/// No request can leave the file: no script, image, frame, style sheet or
/// font reference, and no address but the link back to the lab.
fn self_contained(html: &str, link: &str) -> Result<(), String> {
    // The one script element is the data record, a type no browser runs.
    let html = &match html.split_once("<script type=\"application/json\" id=\"lab-report-data\">") {
        Some((before, after)) => {
            let (data, rest) = after.split_once("</script>").ok_or("unclosed record")?;
            if data.contains('<') {
                return Err("markup in the record".into());
            }
            format!("{before}{rest}")
        }
        None => return Err("no data record".into()),
    };
    let lower = html.to_lowercase();
    for bad in [
        "src=",
        "<script",
        "<img",
        "<iframe",
        "<link",
        "<object",
        "<embed",
        "@import",
        "@font-face",
        "srcset",
        "xlink:href",
    ] {
        if lower.contains(bad) {
            return Err(format!("found {bad}"));
        }
    }
    // `url(` only for the plots' own clip paths.
    for (k, _) in lower.match_indices("url(") {
        if !lower[k..].starts_with("url(#plot") {
            return Err(format!("url( at {k}"));
        }
    }
    let without_link = html.replace(&escape(link), "");
    let lower = without_link.to_lowercase();
    if lower.contains("http:") || lower.contains("https:") || lower.contains("//") {
        return Err("an address other than the link".into());
    }
    Ok(())
}

/// No tag carries an `on…` attribute (text that merely reads "onerror=" is fine).
fn no_handler_attributes(html: &str) -> bool {
    let mut rest = html;
    while let Some(a) = rest.find('<') {
        let tail = &rest[a + 1..];
        let end = tail.find('>').unwrap_or(tail.len());
        // Drop quoted attribute values, then look at attribute names.
        let mut unquoted = String::new();
        let mut quote = None;
        for c in tail[..end].chars() {
            match (quote, c) {
                (None, '"' | '\'') => quote = Some(c),
                (Some(q), c) if c == q => quote = None,
                (None, c) => unquoted.push(c),
                _ => {}
            }
        }
        if unquoted
            .split_whitespace()
            .skip(1)
            .any(|attr| attr.to_lowercase().starts_with("on"))
        {
            return false;
        }
        rest = &tail[end..];
    }
    true
}

fn content_of(id: &str) -> &'static Content {
    crate::find(id).unwrap().content().unwrap()
}

/// Every experiment in its preview state after a long run, with a submitted
/// quiz: every parameter, readout and plot is in the report, each plot once
/// as SVG and once as a data table; the file is balanced, self-contained and
/// small.
#[test]
fn every_experiment_reports_every_parameter_and_plot_self_contained() {
    let mut largest = (0, "");
    for entry in crate::registry() {
        let mut exp = (entry.make)();
        exp.preview();
        let steps = if exp.animated() { 3600 } else { 0 }; // a minute at 60 Hz
        for _ in 0..steps {
            exp.step(Clock::DT_S);
        }
        let content = entry.content().unwrap();
        let questions = crate::quiz::prepare(content, entry.generators, 42).unwrap();
        let answers: Vec<Response> = questions
            .iter()
            .map(|q| match &q.kind {
                PreparedKind::Choice { answer, .. } => Response::Choice(Some(*answer)),
                PreparedKind::Numeric { .. } => Response::Text("1".into()),
            })
            .collect();
        let link = format!(
            "https://lab.example.org/sub/{}",
            crate::route::format(exp.as_ref(), crate::route::Tab::Simulation)
        );
        let html = render(&Report {
            experiment: exp.as_ref(),
            content,
            link: &link,
            date: "2026-11-25 12:00",
            quiz: Some(QuizResult {
                seed: 42,
                questions: &questions,
                answers: &answers,
                submitted: true,
            }),
            note: None,
            student: Student::default(),
            answer_key: AnswerKey::Submitted,
            marks: &[],
            shown: None,
        });
        let id = entry.id;
        balanced(&html).unwrap_or_else(|e| panic!("{id}: {e}"));
        self_contained(&html, &link).unwrap_or_else(|e| panic!("{id}: {e}"));
        // A light report: no frame in the dark theme's bound colour.
        assert!(
            !html.contains("#8c97a3"),
            "{id}: a dark colour in the report"
        );
        assert!(
            html.contains(&format!("<h1>{}</h1>", escape(&content.title))),
            "{id}"
        );
        assert!(
            html.contains(&format!("<p>{}</p>", content.aim[0])),
            "{id}: aim"
        );
        assert!(
            html.contains(&format!("href=\"{}\"", escape(&link))),
            "{id}: link"
        );
        assert!(html.contains("2026-11-25 12:00"), "{id}: date");
        for spec in exp.params() {
            assert!(
                html.contains(&format!("<tr data-param=\"{}\">", spec.key)),
                "{id}: parameter {}",
                spec.key
            );
        }
        for r in exp.readouts() {
            assert!(
                html.contains(&format!("data-readout=\"{}\"", r.key)),
                "{id}: {}",
                r.key
            );
        }
        for t in exp.tables() {
            assert!(
                html.contains(&format!("data-table=\"{}\"", t.key)),
                "{id}: {}",
                t.key
            );
        }
        let plots = exp.plots();
        let mut figures = svgs(&html);
        // The scene first, then one per plot.
        let scene = figures.remove(0);
        assert!(scene.starts_with("<svg class=\"scene\""), "{id}");
        well_formed_svg(scene).unwrap_or_else(|e| panic!("{id} scene: {e}"));
        assert!(scene.len() > 500, "{id}: the scene draws something");
        assert_eq!(figures.len(), plots.len(), "{id}: one svg per plot");
        for (svg, plot) in figures.iter().zip(plots) {
            well_formed_svg(svg).unwrap_or_else(|e| panic!("{id} {}: {e}", plot.key));
            assert!(
                html.contains(&format!("data-plot=\"{}\"", plot.key)),
                "{id}"
            );
            assert!(
                html.contains(&format!("data-plot-table=\"{}\"", plot.key)),
                "{id}"
            );
            if plot.sample_count() > 0 {
                assert!(svg.contains("<path d=\"M"), "{id} {}: a curve", plot.key);
            }
        }
        // The quiz was answered with every choice right.
        let (right, total) = QuizResult {
            seed: 42,
            questions: &questions,
            answers: &answers,
            submitted: true,
        }
        .score();
        assert!(
            html.contains(&format!("Score: {right} / {total}")),
            "{id}: score"
        );
        assert_eq!(html.matches("<tr class=\"right\">").count(), right, "{id}");
        assert_eq!(
            html.matches("<tr class=\"wrong\">").count(),
            total - right,
            "{id}"
        );
        assert_eq!(
            html.matches("<div class=\"line\"></div>").count(),
            OBSERVATION_LINES
        );
        assert!(html.len() < 400_000, "{id}: {} bytes", html.len());
        if html.len() > largest.0 {
            largest = (html.len(), id);
        }
    }
    eprintln!("largest report: {} ({} bytes)", largest.1, largest.0);
}

/// A made-up experiment whose every text is hostile markup.
#[derive(Clone)]
struct Hostile {
    plots: Vec<Plot>,
}

/// A plot with no moment on it (no report moment shown, no mark).
const NO_MOMENTS: Moments<'static> = Moments {
    shown: None,
    marks: Vec::new(),
};

const EVIL: &str = "<script>alert(1)</script><img src=x onerror=alert(2)>\"'&";

const HOSTILE_PARAMS: [ParamSpec; 2] = [
    ParamSpec::slider("k", "<b>K</b>", "<i>m</i>", 0.0, 1.0, 0.1, 0.5),
    ParamSpec::choice("c", "Choice", &["<em>a</em>", "b"], 0),
];

impl Experiment for Hostile {
    fn id(&self) -> &'static str {
        "hostile"
    }
    fn params(&self) -> &'static [ParamSpec] {
        &HOSTILE_PARAMS
    }
    fn param(&self, key: &str) -> Option<f64> {
        match key {
            "k" => Some(0.5),
            "c" => Some(0.0),
            _ => None,
        }
    }
    fn set_param(&mut self, key: &str, _: f64) -> Result<Sanitized, ParamError> {
        Err(ParamError::UnknownKey { key: key.into() })
    }
    fn input(&mut self, _: Input) {}
    fn step(&mut self, _: f64) {}
    fn plots(&self) -> &[Plot] {
        &self.plots
    }
    fn extra_state(&self) -> Vec<(&'static str, String)> {
        vec![("walls", EVIL.into())]
    }
}

impl Presentation for Hostile {
    fn view(&self) -> ViewBox {
        ViewBox::centered(1.0)
    }
    fn scene(&self, out: &mut Scene) {
        out.items.push(crate::scene::Item::Label {
            pos: glam::DVec2::ZERO,
            text: EVIL.into(),
            role: crate::scene::Role::Text,
            offset_px: glam::DVec2::ZERO,
        });
    }
    fn readouts(&self) -> Vec<Readout> {
        vec![Readout::new("r", "<u>r</u>", EVIL)]
    }
    fn status(&self) -> Status {
        Status::new(EVIL, Tone::Bad)
    }
    fn hint(&self) -> &'static str {
        ""
    }
    fn tables(&self) -> Vec<Table> {
        let mut t = Table::new("t", EVIL, &["<th>"]);
        t.push_row(vec![EVIL.into()]);
        vec![t]
    }
}

fn hostile_plot() -> Plot {
    let mut p = Plot::new(
        "evil",
        "<script>t</script>",
        ("<x>", "<s>"),
        ("<y>", "&"),
        vec![Series::new(EVIL, "m", SeriesRole::Primary)],
    );
    for i in 0..5 {
        p.series[0].push(f64::from(i), f64::from(i * i));
    }
    p.markers.push(Marker {
        x: 2.0,
        y: 4.0,
        label: EVIL.into(),
    });
    p.ref_lines.push(RefLine {
        axis: Axis::Y,
        value: 3.0,
        label: EVIL.into(),
    });
    p.bands.push(Band {
        axis: Axis::X,
        lo: 1.0,
        hi: 2.0,
        label: EVIL.into(),
    });
    p
}

/// Text from a link, a note, the student or an experiment never becomes
/// markup: no element, attribute or handler can be injected.
#[test]
fn hostile_text_everywhere_is_escaped() {
    let exp = Hostile {
        plots: vec![hostile_plot()],
    };
    let content = content_of("pid");
    let questions =
        crate::quiz::prepare(content, crate::find("pid").unwrap().generators, 1).unwrap();
    let answers: Vec<Response> = questions
        .iter()
        .map(|_| Response::Text(EVIL.into()))
        .collect();
    let link = format!("https://x.example/#/pid/simulation?a=\"><script>x</script>{EVIL}");
    let html = render(&Report {
        experiment: &exp,
        content,
        link: &link,
        date: EVIL,
        quiz: Some(QuizResult {
            seed: 1,
            questions: &questions,
            answers: &answers,
            submitted: true,
        }),
        note: Some(EVIL),
        student: Student {
            name: EVIL,
            group: EVIL,
            observations: EVIL,
        },
        answer_key: AnswerKey::Submitted,
        marks: &[],
        shown: None,
    });
    let lower = html.to_lowercase();
    // The one script element is the data record (JSON, never run).
    assert_eq!(lower.matches("<script").count(), 1, "script injected");
    assert_eq!(
        lower
            .matches("<script type=\"application/json\" id=\"lab-report-data\">")
            .count(),
        1
    );
    assert!(!lower.contains("<img"), "img injected");
    assert!(!lower.contains("<b>k"), "label markup");
    assert!(!lower.contains("<th>\""), "table header markup");
    assert!(no_handler_attributes(&html), "handler injected");
    assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert!(html.contains("&lt;b&gt;K&lt;/b&gt;"));
    balanced(&html).unwrap();
    for svg in svgs(&html) {
        well_formed_svg(svg).unwrap();
    }
    // Every typed answer is wrong (a choice question got text: blank).
    assert!(html.contains(&format!("Score: 0 / {}", questions.len())));
}

#[test]
fn table_rows_are_evenly_spaced_with_first_and_last() {
    assert_eq!(table_rows(5, 40), vec![0, 1, 2, 3, 4]);
    assert_eq!(table_rows(0, 40), Vec::<usize>::new());
    // k · 99 / 4 = 0, 24.75, 49.5, 74.25, 99.
    assert_eq!(table_rows(100, 5), vec![0, 25, 50, 74, 99]);
    let rows = table_rows(20_000, TABLE_ROWS);
    assert_eq!(rows.len(), TABLE_ROWS);
    assert_eq!((rows[0], rows[TABLE_ROWS - 1]), (0, 19_999));
    assert!(rows.windows(2).all(|w| w[1] > w[0]));
}

/// A long run's table is cut to [`TABLE_ROWS`] rows and says so; its
/// figure is decimated to a few points per bucket, so the report stays small.
#[test]
fn long_series_are_decimated_in_table_and_figure() {
    let mut p = Plot::new(
        "long",
        "Long",
        ("Time", "s"),
        ("x", "m"),
        vec![Series::new("x", "m", SeriesRole::Primary)],
    );
    for i in 0..20_000 {
        let t = f64::from(i) * 0.01;
        p.series[0].push(t, crate::math::sin(t));
    }
    let mut h = String::new();
    data_table(&mut h, &p, 1);
    assert_eq!(h.matches("<tr><td>").count(), TABLE_ROWS);
    assert!(h.contains("30 evenly spaced rows of 20000 samples"), "{h}");
    // First and last samples: t = 0 and t = 199.99.
    assert!(h.contains("<tr><td>0</td>") && h.contains("<tr><td>199.99</td>"));
    let svg = plot_svg(&p, 0, &NO_MOMENTS);
    let vertices = svg.matches('L').count() + 1;
    assert!(vertices <= DRAW_BUCKETS * 4, "{vertices}");
    assert!(svg.len() < 40_000, "{}", svg.len());
}

/// A line from (0, 0) to (10, 10): x spans the plot from the left margin to
/// the right; y is padded by 5 % of its range on each side.
#[test]
fn plot_points_land_where_the_axes_say() {
    let mut p = Plot::new(
        "lin",
        "Line",
        ("x", ""),
        ("y", ""),
        vec![Series::new("y", "", SeriesRole::Primary)],
    );
    p.series[0].push(0.0, 0.0);
    p.series[0].push(10.0, 10.0);
    let svg = plot_svg(&p, 0, &NO_MOMENTS);
    // One legend row: top = 14 + 8 + 12 = 34; bottom = 34 + 280 − 42 − 12 = 260.
    // y ∈ [−0.5, 10.5]: y = 0 → 260 − 0.5/11 · 226 = 249.73; y = 10 → 44.27.
    // x from 64 to 640 − 24 = 616.
    assert!(svg.contains("<path d=\"M64,249.73L616,44.27\""), "{svg}");
    // Ticks 0, 2, …, 10 on x; the first at the left edge.
    assert!(
        svg.contains("<text x=\"64\" y=\"274\" text-anchor=\"middle\" fill=\"#1b1f24\">0</text>"),
        "{svg}"
    );
}

#[test]
fn an_empty_plot_and_an_unsubmitted_quiz_say_so() {
    let mut plot = hostile_plot();
    plot.clear();
    let exp = Hostile { plots: vec![plot] };
    let html = render(&Report {
        experiment: &exp,
        content: content_of("fk"),
        link: "http://localhost/#/fk/simulation",
        date: "today",
        quiz: None,
        note: None,
        student: Student::default(),
        answer_key: AnswerKey::Submitted,
        marks: &[],
        shown: None,
    });
    assert!(html.contains("No data yet: run the simulation first."));
    // The page colours are the table's light ones (the page's stylesheet is
    // held to the same table), and every frame is the light theme's bound:
    // the dark theme's #8c97a3 was printed in a light figure.
    use labcore::layout::page_colours::{GOOD, PAGE};
    for c in PAGE {
        assert!(
            html.contains(&format!("{}:{}", c.var, c.light)),
            "{}",
            c.var
        );
    }
    assert!(html.contains(".status.good{color:var(--good)}"));
    assert_eq!(GOOD.light, "#007a5a");
    let bound = crate::scene::Role::Bound.style().light();
    assert!(html.contains(&format!("stroke=\"{bound}\"")));
    assert!(
        !html.contains("#8c97a3"),
        "the dark theme's bound in a light report"
    );
    assert!(html.contains("No samples yet."));
    assert!(html.contains("had not been submitted"));
    assert!(!html.contains("Score:"));
    assert!(!html.contains("Instructor's note"));
    balanced(&html).unwrap();
}

#[test]
fn log_axis_ticks_read_as_powers_of_ten() {
    // The page's plots label a log axis with the same function.
    use labcore::layout::ticks::log_tick_labels;
    assert_eq!(log_tick_labels(&[1e-6, 1e5]), ["10⁻⁶", "10⁵"]);
    assert_eq!(log_tick_labels(&[0.01, 1000.0]), ["0.01", "1000"]);
    let mut p = hostile_plot();
    p.log_y = true;
    let svg = plot_svg(&p, 3, &NO_MOMENTS);
    well_formed_svg(&svg).unwrap();
    assert!(svg.contains("id=\"plot3-clip\""));
}

#[test]
fn dates_show_local_time_and_offset() {
    assert_eq!(
        date_text(2026, 11, 5, 9, 7, 60),
        "2026-11-05 09:07 (UTC+01:00)"
    );
    assert_eq!(
        date_text(2026, 1, 30, 23, 59, -210),
        "2026-01-30 23:59 (UTC-03:30)"
    );
    assert_eq!(
        date_text(2026, 6, 1, 0, 0, 0),
        "2026-06-01 00:00 (UTC+00:00)"
    );
}

/// World (0, 0)–(2, 1) fills 640 × 320 units, y up: hand-computed positions
/// of a line, a run of raster cells and a thinned tree.
#[test]
fn scene_maps_world_to_picture_with_y_up() {
    use crate::scene::{Item, RasterColour, Role};
    use glam::DVec2;
    let view = ViewBox {
        min: DVec2::ZERO,
        max: DVec2::new(2.0, 1.0),
    };
    let mut scene = Scene::default();
    scene.items.push(Item::Line {
        from: DVec2::ZERO,
        to: DVec2::new(1.0, 1.0),
        width_px: 2.0,
        role: Role::Link,
        dashed: false,
    });
    // Row 0 (bottom): cells 0 and 1 wall, cell 2 free, cell 3 wall.
    scene.items.push(Item::Raster {
        min: DVec2::ZERO,
        cell_m: 0.5,
        cols: 4,
        rows: 2,
        cells: vec![1, 1, 0, 1, 0, 0, 0, 0],
        palette: vec![RasterColour {
            role: Role::Obstacle,
            alpha: 0.8,
        }],
    });
    let edges = scene_svg::MAX_SEGMENTS + 5;
    scene.items.push(Item::Segments {
        segments: vec![(DVec2::ZERO, DVec2::new(0.5, 0.5)); edges],
        width_px: 1.0,
        role: Role::Visited,
    });
    let (svg, notes) = scene_svg::scene_svg(&scene, view);
    assert!(svg.starts_with("<svg class=\"scene\" viewBox=\"0 0 640 320\""));
    assert!(svg.contains("<line x1=\"0\" y1=\"320\" x2=\"320\" y2=\"0\" stroke=\"#0072B2\""));
    // Cells are 160 units; the bottom row's top edge is at y = 320 − 160:
    // a run of two at the left, one at x = 480.
    assert!(svg.contains(
        "d=\"M0,160h320v160h-320zM480,160h160v160h-160z\" fill=\"#5f6a75\" fill-opacity=\"0.8\""
    ));
    assert_eq!(
        svg.matches("M0 320l160 -160").count(),
        scene_svg::MAX_SEGMENTS
    );
    assert_eq!(
        notes,
        vec![format!(
            "the first {} of {edges} edges drawn",
            scene_svg::MAX_SEGMENTS
        )]
    );
    well_formed_svg(&svg).unwrap();
}

/// Whether the canvas paints something for `item` (labweb's `draw.rs`):
/// batches with members, lines with enough points, grids with a lit cell. The
/// focus ring is the page's own and not part of an experiment's scene.
fn screen_draws(item: &crate::scene::Item, view: ViewBox) -> bool {
    use crate::scene::Item;
    match item {
        Item::Points { points, .. } => !points.is_empty(),
        Item::Segments { segments, .. } => !segments.is_empty(),
        Item::SegmentLayer { layer, .. } => !layer.is_empty(),
        Item::Arrows { arrows, .. } => !arrows.is_empty(),
        Item::Arrow { from, to, .. } => (*to - *from).length() > 1e-9,
        Item::Polyline { points, .. } => points.len() >= 2,
        Item::Polygon { points, .. } => points.len() >= 3,
        Item::Heatmap { values, .. } => values.iter().any(|v| *v > 0.0),
        Item::Raster { cells, palette, .. } | Item::VersionedRaster { cells, palette, .. } => cells
            .iter()
            .any(|&c| c > 0 && usize::from(c) <= palette.len()),
        Item::OffView { at, .. } => {
            !(at.x >= view.min.x && at.x <= view.max.x && at.y >= view.min.y && at.y <= view.max.y)
        }
        Item::FocusRing { .. } => false,
        _ => true,
    }
}

/// The picture of one item alone: the SVG elements drawn for it (the
/// picture's own background and frame left out) and the segments of its
/// batch paths (`M` commands of `l`-segment paths).
fn drawn_alone(item: &crate::scene::Item, view: ViewBox) -> (usize, usize) {
    let mut scene = Scene::default();
    scene.items.push(item.clone());
    let (svg, _) = scene_svg::scene_svg(&scene, view);
    let elements = svg.matches('<').count() - svg.matches("</").count() - 3;
    let segments = svg
        .split("<path d=\"")
        .skip(1)
        .map(|p| &p[..p.find('"').unwrap()])
        .filter(|d| d.contains('l'))
        .map(|d| d.matches('M').count())
        .sum();
    (elements, segments)
}

/// Segments a batch item holds (a tree's edges), 0 for other items.
fn batch_len(item: &crate::scene::Item) -> usize {
    use crate::scene::Item;
    match item {
        Item::Segments { segments, .. } => segments.len(),
        Item::SegmentLayer { layer, .. } => layer.len(),
        _ => 0,
    }
}

/// Every experiment, in its preview after a minute's run and after each of
/// its actions and a ten-second run: every item the canvas paints is drawn in
/// the report's picture, and every batch of segments with as many segments as
/// the live scene holds (up to the stated limit).
#[test]
fn report_scene_draws_every_item_the_live_scene_draws_for_every_experiment() {
    let mut kinds_seen = std::collections::BTreeSet::new();
    for entry in crate::registry() {
        let id = entry.id;
        let mut states: Vec<Box<dyn Lab>> = Vec::new();
        let mut exp = (entry.make)();
        exp.preview();
        for _ in 0..if exp.animated() { 3600 } else { 0 } {
            exp.step(Clock::DT_S);
        }
        states.push(exp);
        let probe = (entry.make)();
        for action in probe.actions() {
            let mut exp = (entry.make)();
            exp.preview();
            if exp.action(action.key).is_err() {
                continue;
            }
            for _ in 0..600 {
                exp.step(Clock::DT_S);
            }
            states.push(exp);
        }
        for exp in &states {
            let view = exp.view();
            let mut scene = Scene::default();
            exp.scene(&mut scene);
            for item in &scene.items {
                if !screen_draws(item, view) {
                    continue;
                }
                let kind = format!("{item:?}");
                let kind = kind[..kind.find([' ', '{']).unwrap_or(kind.len())].to_owned();
                let (elements, segments) = drawn_alone(item, view);
                assert!(elements > 0, "{id}: the report leaves out a {kind}");
                let live = batch_len(item);
                if live > 0 {
                    assert_eq!(
                        segments,
                        live.min(scene_svg::MAX_SEGMENTS),
                        "{id}: {kind} of {live} segments"
                    );
                }
                kinds_seen.insert(kind);
            }
        }
    }
    // The kept kinds are among those checked.
    for kind in ["SegmentLayer", "VersionedRaster"] {
        assert!(kinds_seen.contains(kind), "{kind} seen in {kinds_seen:?}");
    }
}

/// The RRT* run of the issue: `iters=20000&batch=400`, Grow tree, stepped to
/// "done". The report draws every edge of the tree the screen shows (nodes − 1).
#[test]
fn rrtstar_report_draws_the_whole_tree_after_the_longest_run() {
    let entry = crate::find("rrtstar").unwrap();
    let mut exp = (entry.make)();
    exp.set_param("iters", 20_000.0).unwrap();
    exp.set_param("batch", 400.0).unwrap();
    exp.action("grow").unwrap();
    let mut steps = 0;
    while !exp.status().text.starts_with("done") {
        exp.step(Clock::DT_S);
        steps += 1;
        assert!(steps < 1000, "done after 50 batches");
    }
    let nodes: usize = exp
        .readouts()
        .iter()
        .find(|r| r.key == "nodes")
        .unwrap()
        .value
        .replace(',', "")
        .parse()
        .unwrap();
    assert!(nodes > 10_000, "{nodes} nodes");
    let html = render(&Report {
        experiment: exp.as_ref(),
        content: entry.content().unwrap(),
        link: "http://localhost/#/rrtstar/simulation",
        date: "today",
        quiz: None,
        note: None,
        student: Student::default(),
        answer_key: AnswerKey::Submitted,
        marks: &[],
        shown: None,
    });
    let scene = svgs(&html)[0];
    // The tree is the one path in the Visited colour.
    let tree = scene
        .split("<path d=\"")
        .skip(1)
        .find(|p| p.contains("stroke=\"#56B4E9\""))
        .expect("the tree is drawn");
    assert_eq!(
        tree[..tree.find('"').unwrap()].matches('M').count(),
        nodes - 1
    );
}

/// A report of experiment `id` with every answer the first option (or "1"),
/// drawn from `seed`, `submitted` or not, with `key` and `student`.
fn quiz_report(
    id: &str,
    seed: u64,
    submitted: bool,
    key: AnswerKey,
    student: Student<'_>,
) -> (String, usize, usize) {
    let entry = crate::find(id).unwrap();
    let exp = (entry.make)();
    let content = entry.content().unwrap();
    let questions = crate::quiz::prepare(content, entry.generators, seed).unwrap();
    let answers: Vec<Response> = questions
        .iter()
        .map(|q| match &q.kind {
            PreparedKind::Choice { .. } => Response::Choice(Some(0)),
            PreparedKind::Numeric { .. } => Response::Text("1".into()),
        })
        .collect();
    let quiz = QuizResult {
        seed,
        questions: &questions,
        answers: &answers,
        submitted,
    };
    let (right, total) = quiz.score();
    let html = render(&Report {
        experiment: exp.as_ref(),
        content,
        link: "http://localhost/#/pid/simulation",
        date: "today",
        quiz: Some(quiz),
        note: None,
        student,
        answer_key: key,
        marks: &[],
        shown: None,
    });
    (html, right, total)
}

/// Name, Group and Observations typed before the report are printed in it
/// (escaped, line breaks kept), in fields the file keeps editable.
#[test]
fn report_fields_print_the_typed_name_group_and_observations() {
    let student = Student {
        name: "  Ada <Lovelace> ",
        group: "B-2 & co",
        observations: "The overshoot grew with Kp.\nKd damped it.",
    };
    let (html, _, _) = quiz_report("pid", 7, true, AnswerKey::Submitted, student);
    assert!(html.contains(
        "<dd class=\"field\" contenteditable=\"true\" data-field=\"name\">Ada &lt;Lovelace&gt;</dd>"
    ));
    assert!(html.contains(
        "<dd class=\"field\" contenteditable=\"true\" data-field=\"group\">B-2 &amp; co</dd>"
    ));
    assert!(html
        .contains("data-field=\"observations\">The overshoot grew with Kp.\nKd damped it.</div>"));
    balanced(&html).unwrap();
    // Left empty: blank fields to write on, and the full lined box.
    let (blank, _, _) = quiz_report("pid", 7, true, AnswerKey::Submitted, Student::default());
    assert!(blank.contains("data-field=\"name\"></dd>"));
    assert_eq!(
        blank.matches("<div class=\"line\"></div>").count(),
        OBSERVATION_LINES
    );
}

fn expected_cells(html: &str) -> usize {
    html.matches("<td class=\"expected\">").count()
}

/// `key=never`: a submitted quiz is shown with its answers and marks but no
/// expected answer anywhere.
#[test]
fn answer_key_never_hides_the_expected_answers() {
    let (html, right, total) = quiz_report("fk", 3, true, AnswerKey::Never, Student::default());
    assert!(html.contains(&format!("Score: {right} / {total}")));
    assert_eq!(expected_cells(&html), 0);
    assert!(!html.contains(">Expected<"));
    assert!(html.contains("Expected answers are not shown"));
    assert_eq!(
        html.matches("<tr class=\"right\">").count() + html.matches("<tr class=\"wrong\">").count(),
        total
    );
}

/// `key=submitted`: expected answers once submitted, nothing before.
#[test]
fn answer_key_submitted_shows_them_after_submission_only() {
    let (html, _, total) = quiz_report("fk", 3, true, AnswerKey::Submitted, Student::default());
    assert_eq!(expected_cells(&html), total);
    let (before, _, _) = quiz_report("fk", 3, false, AnswerKey::Submitted, Student::default());
    assert_eq!(expected_cells(&before), 0);
    assert!(before.contains("had not been submitted"));
}

/// `key=always`: the questions with their expected answers even before
/// submission (no score), and after it.
#[test]
fn answer_key_always_shows_them_before_submission_too() {
    let (before, _, total) = quiz_report("fk", 3, false, AnswerKey::Always, Student::default());
    assert_eq!(expected_cells(&before), total);
    assert!(!before.contains("Score:"));
    assert!(before.contains("\"quiz\":null"), "no score to check");
    let (after, _, _) = quiz_report("fk", 3, true, AnswerKey::Always, Student::default());
    assert_eq!(expected_cells(&after), total);
}

/// The default: never when the link fixes a class-wide quiz seed, else after
/// submission; a link's own choice wins, and round-trips.
#[test]
fn answer_key_defaults_to_never_when_the_link_fixes_a_quiz_seed() {
    use crate::route::{parse, Page};
    let ids = ["fk"];
    let class = parse("#/fk/simulation?quiz=123", &ids);
    assert_eq!(
        AnswerKey::in_force(class.instructor.answer_key, class.quiz_seed),
        AnswerKey::Never
    );
    let own = parse("#/fk/simulation", &ids);
    assert_eq!(
        AnswerKey::in_force(own.instructor.answer_key, own.quiz_seed),
        AnswerKey::Submitted
    );
    for choice in AnswerKey::ALL {
        let r = parse(
            &format!("#/fk/simulation?quiz=123&key={}", choice.slug()),
            &ids,
        );
        assert!(r.notices.is_empty(), "{:?}", r.notices);
        assert_eq!(
            AnswerKey::in_force(r.instructor.answer_key, r.quiz_seed),
            choice
        );
        assert!(r
            .instructor
            .query()
            .contains(&format!("key={}", choice.slug())));
        assert!(matches!(r.page, Page::Experiment { ref params, .. } if params.is_empty()));
    }
    let bad = parse("#/fk/simulation?key=sometimes", &ids);
    assert_eq!(bad.instructor.answer_key, None);
    assert_eq!(
        bad.notices,
        vec!["Answer key “sometimes” is not never, submitted or always; ignored.".to_owned()]
    );
}

/// The record a checker reads: the report's id, seed, answers and score as
/// JSON, which grades again to the printed score; hostile typed answers
/// cannot close the element.
#[test]
fn report_data_record_holds_id_seed_answers_and_the_printed_score() {
    let (html, right, total) =
        quiz_report("ik", u64::MAX, true, AnswerKey::Never, Student::default());
    let start = html
        .find("<script type=\"application/json\" id=\"lab-report-data\">")
        .unwrap();
    let body = &html[start..];
    let json = &body[body.find('>').unwrap() + 1..body.find("</script>").unwrap()];
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    assert_eq!(v["report"], 1);
    assert_eq!(v["id"], "ik");
    let quiz = &v["quiz"];
    assert_eq!(quiz["seed"], u64::MAX.to_string());
    assert_eq!(quiz["score"], serde_json::json!([right, total]));
    assert!(html.contains(&format!("Score: {right} / {total}")));
    // Grading the record's answers again gives the printed score.
    let entry = crate::find("ik").unwrap();
    let questions =
        crate::quiz::prepare(entry.content().unwrap(), entry.generators, u64::MAX).unwrap();
    let answers: Vec<Response> = quiz["answers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| match a {
            serde_json::Value::Number(k) => Response::Choice(Some(k.as_u64().unwrap() as usize)),
            serde_json::Value::String(t) => Response::Text(t.clone()),
            _ => Response::Choice(None),
        })
        .collect();
    assert_eq!(answers.len(), total);
    let again = QuizResult {
        seed: u64::MAX,
        questions: &questions,
        answers: &answers,
        submitted: true,
    };
    assert_eq!(again.score(), (right, total));
    // Typed text that tries to end the element stays inside it.
    let mut out = String::new();
    json_string(&mut out, "</script><b>\"\\\n\u{2028}");
    assert_eq!(
        out,
        "\"\\u003c/script\\u003e\\u003cb\\u003e\\\"\\\\\\u000a\\u2028\""
    );
    assert_eq!(
        serde_json::from_str::<String>(&out).unwrap(),
        "</script><b>\"\\\n\u{2028}"
    );
}

#[test]
fn the_report_scene_draws_the_grid_in_the_canvas_grid_colour() {
    // The grid's colour had drifted: #d5dbe1 in the report, #e3e7ec on the
    // canvas (web/style.css). Both come from the style table now.
    let mut scene = Scene::default();
    scene.axes(ViewBox::centered(1.0));
    let (svg, _) = scene_svg::scene_svg(&scene, ViewBox::centered(1.0));
    assert!(svg.contains("stroke=\"#e3e7ec\""), "{svg}");
    assert!(!svg.contains("#d5dbe1"), "{svg}");
    assert_eq!(crate::scene::Role::Grid.style().light(), "#e3e7ec");
}

#[test]
fn the_report_plot_draws_reference_lines_and_bands_as_the_canvas_plot_does() {
    // The report's plots had drifted from the canvas's: reference lines
    // dashed 5 5 (canvas 6 4), bands at opacity 0.18 (canvas 0.22).
    let svg = plot_svg(&hostile_plot(), 0, &NO_MOMENTS);
    assert!(
        svg.contains("stroke=\"#5f6a75\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\""),
        "{svg}"
    );
    assert!(
        svg.contains("fill=\"#E69F00\" fill-opacity=\"0.22\""),
        "{svg}"
    );
    assert!(!svg.contains("stroke-dasharray=\"5 5\""), "{svg}");
}

/// The section of mark `t` (its `<section class="mark" …>` … `</section>`).
fn mark_section<'h>(html: &'h str, t: &str) -> &'h str {
    let start = html
        .find(&format!("<section class=\"mark\" data-mark-t=\"{t}\">"))
        .unwrap_or_else(|| panic!("no section for the mark at {t}"));
    let end = start + html[start..].find("</section>").unwrap();
    &html[start..end]
}

/// Issue 26 §3: a mark's section shows the state of its step, restored
/// through the timeline: the readouts and the scene the live run had at
/// that step, for every experiment with a timeline, marks mid-run and at a
/// step between two snapshots.
#[test]
fn report_mark_section_shows_the_live_runs_state_at_the_marked_step() {
    use labcore::timeline::Timeline;
    let mut checked = 0;
    for entry in crate::registry() {
        let mut exp = (entry.make)();
        if !exp.animated() {
            continue;
        }
        exp.preview();
        let mut timeline = Timeline::new(exp.as_ref(), 0);
        let marked_steps = [45_u64, 100];
        let mut live = Vec::new();
        for step in 1..=150 {
            exp.step(Clock::DT_S);
            timeline.stepped(exp.as_ref());
            if marked_steps.contains(&step) {
                let mut scene = Scene::default();
                exp.scene(&mut scene);
                live.push((exp.readouts(), scene_svg::scene_svg(&scene, exp.view()).0));
            }
        }
        let states: Vec<Box<dyn Lab>> = marked_steps
            .iter()
            .map(|&s| {
                timeline
                    .state_at(s, &mut |e: &mut dyn Lab| e.step(Clock::DT_S))
                    .1
            })
            .collect();
        let marks: Vec<MarkedMoment<'_>> = marked_steps
            .iter()
            .zip(&states)
            .map(|(&s, state)| MarkedMoment {
                t_s: s as f64 * Clock::DT_S,
                state: state.as_ref(),
            })
            .collect();
        let html = render(&Report {
            experiment: exp.as_ref(),
            content: content_of(entry.id),
            link: "#/x",
            date: "2026-11-27 09:00",
            quiz: None,
            note: None,
            student: Student::default(),
            answer_key: AnswerKey::Submitted,
            marks: &marks,
            shown: None,
        });
        let id = entry.id;
        balanced(&html).unwrap_or_else(|e| panic!("{id}: {e}"));
        assert!(html.contains("<h2>Marked moments</h2>"), "{id}");
        for ((t, (readouts, svg)), n) in ["0.75", "1.67"].iter().zip(&live).zip(1..) {
            let section = mark_section(&html, t);
            assert!(
                section.contains(&format!("<h3>Mark {n}: t = {t} s</h3>")),
                "{id}"
            );
            assert!(
                section.contains(svg.as_str()),
                "{id} at {t}: the scene differs"
            );
            for r in readouts {
                let row = format!(
                    "<tr data-readout=\"{}\"><th scope=\"row\">{}</th><td class=\"num\">{}</td></tr>",
                    escape(r.key),
                    escape(r.label),
                    escape(&r.value)
                );
                assert!(section.contains(&row), "{id} at {t}: {row}");
            }
        }
        checked += 1;
    }
    assert!(checked >= 9, "only {checked} experiments with a timeline");
}

/// PID's Procedure step 9 as the page leaves it: Kp = 25, Ki = 0, Kd = 2,
/// c = 1, run to its end, the timeline back at step 40 (t = 0.67 s, the
/// peak). Returns the run's end and the state at the moment.
fn pid_scrubbed_to_the_peak() -> (Box<dyn Lab>, Box<dyn Lab>) {
    use labcore::timeline::Timeline;
    let mut exp = (crate::find("pid").unwrap().make)();
    for (k, v) in [("kp", 25.0), ("ki", 0.0), ("kd", 2.0), ("c", 1.0)] {
        exp.set_param(k, v).unwrap();
    }
    let mut timeline = Timeline::new(exp.as_ref(), 0);
    while exp.status().phase != crate::experiment::Phase::Ended {
        exp.step(Clock::DT_S);
        timeline.stepped(exp.as_ref());
    }
    let (at, moment) = timeline.state_at(40, &mut |e: &mut dyn Lab| e.step(Clock::DT_S));
    assert_eq!(at, 40);
    (exp, moment)
}

/// The report of `end` with the moment `moment` (step 40) on screen and
/// marked or not.
fn report_of_a_moment(end: &dyn Lab, moment: &dyn Lab, marked: bool) -> String {
    let m = MarkedMoment {
        t_s: 40.0 * Clock::DT_S,
        state: moment,
    };
    let marks = [m];
    render(&Report {
        experiment: end,
        content: content_of("pid"),
        link: "#/pid/simulation?kp=25&ki=0&kd=2&run=0&at=0.67&marks=0.67",
        date: "2026-12-07 10:00",
        quiz: None,
        note: None,
        student: Student::default(),
        answer_key: AnswerKey::Submitted,
        marks: if marked { &marks } else { &[] },
        shown: Some(m),
    })
}

/// Issue 53 §2: a report made while the page shows a past moment shows the
/// whole run (its readouts and plots to the end: settling time 2.25 s, the
/// response's 668 samples to 6.67 s), the moment on screen as a line on
/// every plot at its plot x (0.66 s, the control period's last sample) and
/// in a section of its own (Position x 1.374 m, the peak the Procedure
/// names), and a triangle at the mark on every plot: one on the response
/// (its one run series), four on the effort (u, P, I, D).
#[test]
fn a_report_made_at_a_past_moment_shows_the_whole_run_with_the_moment_and_the_marks() {
    let (end, moment) = pid_scrubbed_to_the_peak();
    let html = report_of_a_moment(end.as_ref(), moment.as_ref(), true);
    balanced(&html).unwrap();
    let readout = |html: &str, key: &str| {
        let at = html
            .find(&format!("<tr data-readout=\"{key}\">"))
            .unwrap_or_else(|| panic!("no readout {key}"));
        let cell = &html[at..];
        let cell = &cell[cell.find("<td class=\"num\">").unwrap() + 16..];
        cell[..cell.find('<').unwrap()].to_owned()
    };
    let results = &html[html.find("<section class=\"results\">").unwrap()..];
    let results = &results[..results.find("</section>").unwrap()];
    assert_eq!(readout(results, "settling"), "2.25 s");
    assert!(results.contains("The simulation at the run&#39;s end."));
    let response = &html[html
        .find("<figure class=\"plot\" data-plot=\"response\">")
        .unwrap()..];
    let response = &response[..response.find("</figure>").unwrap()];
    assert!(
        response.contains("position x: 668 samples"),
        "the whole run"
    );
    let cursor = &response[response.find("<g class=\"cursor\" data-x=\"").unwrap() + 26..];
    let x: f64 = cursor[..cursor.find('"').unwrap()].parse().unwrap();
    assert_eq!(format!("{x:.2}"), "0.66");
    assert!(cursor.contains("<title>t = 0.67 s</title>"));
    assert_eq!(response.matches("<path class=\"mark\"").count(), 1);
    assert!(response.contains(
        "The vertical line marks the moment on screen when the report was made, t = 0.67 s. A triangle marks each marked moment."
    ));
    let effort = &html[html
        .find("<figure class=\"plot\" data-plot=\"effort\">")
        .unwrap()..];
    let effort = &effort[..effort.find("</figure>").unwrap()];
    assert_eq!(effort.matches("<path class=\"mark\"").count(), 4);
    assert!(effort.contains("<g class=\"cursor\""));
    // The moment is the mark's section, said to be the one on screen.
    let section = mark_section(&html, "0.67");
    assert!(section.contains("<h3>Mark 1: t = 0.67 s, on screen when the report was made</h3>"));
    assert_eq!(readout(section, "x"), "1.374 m");
    assert!(!html.contains("class=\"moment\""));
    // Not marked: a section of its own, and no triangle.
    let html = report_of_a_moment(end.as_ref(), moment.as_ref(), false);
    balanced(&html).unwrap();
    let start = html
        .find("<section class=\"moment\" data-moment-t=\"0.67\">")
        .unwrap();
    let section = &html[start..start + html[start..].find("</section>").unwrap()];
    assert!(section.contains("<h3>On screen when the report was made: t = 0.67 s</h3>"));
    assert_eq!(readout(section, "x"), "1.374 m");
    assert!(!html.contains("<path class=\"mark\""));
    assert!(!html.contains("Marked moments"));
    // A rolling window (the last second of the run) reaches back to the
    // moment: its line is drawn.
    let mut sheet = Sheet::of(&Report {
        experiment: end.as_ref(),
        content: content_of("pid"),
        link: "#/pid/simulation",
        date: "2026-12-07 10:00",
        quiz: None,
        note: None,
        student: Student::default(),
        answer_key: AnswerKey::Submitted,
        marks: &[],
        shown: Some(MarkedMoment {
            t_s: 40.0 * Clock::DT_S,
            state: moment.as_ref(),
        }),
    });
    sheet.plots[0].window = crate::plot::XWindow::Rolling(1.0);
    let html = render_sheet(&sheet);
    let response = &html[html.find("data-plot=\"response\"").unwrap()..];
    assert!(response[..response.find("</figure>").unwrap()].contains("<g class=\"cursor\""));
}

/// The text elements of `svg` with `text-anchor="{anchor}"` and the text ink.
fn texts_anchored<'a>(svg: &'a str, anchor: &str) -> Vec<&'a str> {
    let open = format!(
        "text-anchor=\"{anchor}\" fill=\"{}\">",
        crate::scene::Role::Text.style().light()
    );
    svg.split(open.as_str())
        .skip(1)
        .map(|t| &t[..t.find("</text>").unwrap()])
        .collect()
}

/// Issue 54 §1: every experiment's default scene and plots, through the
/// report's painter, say what the canvas's geometry says. The scale bar's
/// text is the one the canvas's map ([`WorldMap`], the canvas's `Viewport`)
/// gives at the picture's size; the tick texts follow the page's one rule
/// (`labcore::layout::ticks`): never two alike on an axis, one count of
/// decimals per linear axis, powers of ten on a log axis written as a
/// textbook writes them, never `1e3`.
#[test]
fn every_experiment_s_scale_bar_and_ticks_read_as_on_the_page() {
    use labcore::layout::map::WorldMap;
    use labcore::layout::scale_bar::{ScaleBar, SCALE_BAR_MAX_PX};
    let (mut bars, mut axes) = (0, 0);
    for entry in crate::registry() {
        let id = entry.id;
        let mut exp = (entry.make)();
        exp.preview();
        let view = exp.view();
        let mut scene = Scene::default();
        exp.scene(&mut scene);
        if scene
            .items
            .iter()
            .any(|i| matches!(i, crate::scene::Item::ScaleBar))
        {
            let (svg, _) = scene_svg::scene_svg(&scene, view);
            let size = svg.split("viewBox=\"0 0 ").nth(1).unwrap();
            let mut wh = size[..size.find('"').unwrap()].split(' ');
            let w: f64 = wh.next().unwrap().parse().unwrap();
            let h: f64 = wh.next().unwrap().parse().unwrap();
            let canvas = WorldMap::fit(view, w, h);
            let bar = ScaleBar::fit(canvas.scale_px_per_m, SCALE_BAR_MAX_PX).unwrap();
            assert!(
                svg.contains(&format!(">{}</text>", bar.label)),
                "{id}: the report lacks the canvas's scale bar `{}`",
                bar.label
            );
            assert!(!svg.contains(" cm</text>"), "{id}");
            bars += 1;
        }
        for (i, plot) in exp.plots().iter().enumerate() {
            let svg = plot_svg(plot, i, &NO_MOMENTS);
            for (labels, log) in [
                (texts_anchored(&svg, "middle"), false),
                (texts_anchored(&svg, "end"), plot.log_y),
            ] {
                // The last "middle" text is the x axis title, not a tick.
                let labels: Vec<&str> = labels
                    .into_iter()
                    .filter(|l| l.chars().all(|c| !c.is_alphabetic() || c == 'e'))
                    .collect();
                if labels.len() < 2 {
                    continue;
                }
                axes += 1;
                for (k, a) in labels.iter().enumerate() {
                    assert!(!labels[k + 1..].contains(a), "{id} plot {i}: {labels:?}");
                }
                if log {
                    assert!(labels.iter().all(|l| !l.contains('e')), "{id}: {labels:?}");
                } else {
                    let decimals = |l: &&str| l.split('.').nth(1).map_or(0, str::len);
                    let d = decimals(&labels[0]);
                    assert!(
                        labels.iter().all(|l| decimals(l) == d || l.contains('e')),
                        "{id} plot {i}: {labels:?}"
                    );
                }
            }
        }
    }
    assert!(bars >= 2, "only {bars} experiments draw a scale bar");
    assert!(axes >= 10, "only {axes} axes with ticks");
}
