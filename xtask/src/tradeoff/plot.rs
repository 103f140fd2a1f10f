//! A dependency-free SVG scatter plot with logarithmic axes, for error-vs-cost figures.

use std::fmt::Write as _;

/// One labelled point.
#[derive(Debug, Clone)]
pub struct Point {
    /// Horizontal value (> 0; log axis).
    pub x: f64,
    /// Vertical value (> 0; log axis). Zero or negative values are drawn on the floor.
    pub y: f64,
    /// Short label drawn beside the point.
    pub label: String,
}

/// Points sharing a colour and a legend entry.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// The points.
    pub points: Vec<Point>,
}

/// A log–log scatter plot.
#[derive(Debug, Clone)]
pub struct Plot {
    /// Title on top.
    pub title: String,
    /// Horizontal axis label (with unit).
    pub x_label: String,
    /// Vertical axis label (with unit).
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
}

const COLOURS: &[&str] = &[
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
];

fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
        lo = lo.min(v.log10());
        hi = hi.max(v.log10());
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Plot {
    /// Renders the plot as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let (width, height) = (900.0, 560.0);
        let (left, right, top, bottom) = (90.0, 220.0, 50.0, 70.0);
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let (x_lo, x_hi) = log_range(all().map(|p| p.x));
        let (y_lo, y_hi) = log_range(all().map(|p| p.y));
        let plot_w = width - left - right;
        let plot_h = height - top - bottom;
        let map_x = |x: f64| left + (x.max(1e-300).log10() - x_lo) / (x_hi - x_lo) * plot_w;
        let map_y = |y: f64| {
            let v = if y > 0.0 { y.log10().max(y_lo) } else { y_lo };
            top + plot_h - (v - y_lo) / (y_hi - y_lo) * plot_h
        };
        let mut svg = String::new();
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(
            svg,
            r#"<rect width="100%" height="100%" fill="white"/><text x="{}" y="28" font-size="16" text-anchor="middle">{}</text>"#,
            left + plot_w / 2.0,
            escape(&self.title)
        );
        // Decade grid lines and tick labels.
        for d in x_lo as i32..=x_hi as i32 {
            let x = map_x(10f64.powi(d));
            let _ = writeln!(
                svg,
                r##"<line x1="{x:.1}" y1="{top}" x2="{x:.1}" y2="{}" stroke="#ddd"/><text x="{x:.1}" y="{}" text-anchor="middle">1e{d}</text>"##,
                top + plot_h,
                top + plot_h + 18.0
            );
        }
        for d in y_lo as i32..=y_hi as i32 {
            let y = map_y(10f64.powi(d));
            let _ = writeln!(
                svg,
                r##"<line x1="{left}" y1="{y:.1}" x2="{}" y2="{y:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">1e{d}</text>"##,
                left + plot_w,
                left - 6.0,
                y + 4.0
            );
        }
        let _ = writeln!(
            svg,
            r#"<rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}" fill="none" stroke="black"/>"#
        );
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            left + plot_w / 2.0,
            height - 20.0,
            escape(&self.x_label)
        );
        let _ = writeln!(
            svg,
            r#"<text transform="translate(24,{}) rotate(-90)" text-anchor="middle">{}</text>"#,
            top + plot_h / 2.0,
            escape(&self.y_label)
        );
        for (i, series) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            for p in &series.points {
                let (x, y) = (map_x(p.x), map_y(p.y));
                let _ = writeln!(
                    svg,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="{colour}"/><text x="{:.1}" y="{:.1}" font-size="9" fill="{colour}">{}</text>"#,
                    x + 6.0,
                    y - 4.0,
                    escape(&p.label)
                );
            }
            let ly = top + 10.0 + 18.0 * i as f64;
            let lx = left + plot_w + 16.0;
            let _ = writeln!(
                svg,
                r#"<circle cx="{lx}" cy="{ly}" r="5" fill="{colour}"/><text x="{}" y="{}">{}</text>"#,
                lx + 10.0,
                ly + 4.0,
                escape(&series.name)
            );
        }
        svg.push_str("</svg>\n");
        svg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_land_inside_the_frame_and_labels_are_escaped() {
        let plot = Plot {
            title: "a < b".into(),
            x_label: "cost (s)".into(),
            y_label: "error".into(),
            series: vec![Series {
                name: "s".into(),
                points: vec![
                    Point {
                        x: 1e-6,
                        y: 1e-3,
                        label: "p1".into(),
                    },
                    Point {
                        x: 1e-3,
                        y: 0.0,
                        label: "zero error".into(),
                    },
                ],
            }],
        };
        let svg = plot.to_svg();
        assert!(svg.contains("a &lt; b"));
        assert_eq!(
            svg.matches("<circle").count(),
            3,
            "two points and one legend dot"
        );
        // Every circle centre lies within the plot frame (left 90, right 680, top 50, bottom 490).
        for cap in svg.split("<circle cx=\"").skip(1) {
            let mut nums = cap.split('"');
            let cx: f64 = nums.next().unwrap().parse().unwrap();
            let cy: f64 = nums.nth(1).unwrap().parse().unwrap();
            assert!(
                (90.0..=700.0).contains(&cx) && (50.0..=490.0).contains(&cy),
                "{cx} {cy}"
            );
        }
    }
}
