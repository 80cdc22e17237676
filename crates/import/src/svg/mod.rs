//! SVG in: every subpath of `<path>`, `<line>`, `<polyline>`, `<polygon>`, `<rect>` (rounded
//! corners), `<circle>` and `<ellipse>` — through `<g>`, `<use>` and transforms — becomes one
//! `path` curve in the root's user units, y flipped so that it is seen as a browser shows
//! the file. Arcs, circles, ellipses and rounded corners are exact rational quadratics.
//! The curve's colour is its stroke (with its opacity), or its fill when it has no stroke
//! (a filled shape is drawn as its outline); a gradient gives its first stop's colour.
//! What is not a curve is left out with one warning listing it.
//!
//! XML is read by `roxmltree` (no DTD: no entity expansion), path data, transforms,
//! lengths and colours by `svgtypes`, `<style>` sheets by `simplecss`.

mod dash;
pub mod geometry;

use std::collections::{BTreeMap, HashMap};

use glam::{DAffine2, DVec2};
use roxmltree::{Document, Node};
use splinescope_core::geom::{Curve, Path, PathSegment};
use splinescope_core::ops::{Cap, Join};
use splinescope_encoding::{Color, MAX_MITER_LIMIT, StrokeShape};
use splinescope_io::limits;
use splinescope_scene::format::{SceneCurve, Style};

use crate::{ImportError, Imported};
use geometry::{Subpath, path_data};

/// A colour with its alpha as read, before the scene's colour type.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rgba([u8; 4]);

/// A paint as computed for an element.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Paint {
    None,
    Color(Rgba),
}

/// The properties inherited down the tree, as far as they matter here.
#[derive(Debug, Clone)]
struct Computed {
    stroke: Paint,
    fill: Paint,
    stroke_opacity: f64,
    fill_opacity: f64,
    /// `color`, for `currentColor`.
    color: Rgba,
    /// The product of the ancestors' `opacity` (not inherited, but it multiplies).
    opacity: f64,
    hidden: bool,
    /// `stroke-width` in user units (inherited; default 1).
    stroke_width: f64,
    /// `vector-effect: non-scaling-stroke` (not inherited): the width is in pixels.
    non_scaling: bool,
    /// `stroke-linecap`, `stroke-linejoin`, `stroke-miterlimit` (inherited).
    stroke_shape: StrokeShape,
    /// `stroke-dasharray` in user units (inherited): `None` for a solid stroke.
    dasharray: Option<std::rc::Rc<[f64]>>,
    /// A `stroke-dasharray` in relative units (not read: the stroke is drawn solid).
    dash_relative: bool,
    /// `stroke-dashoffset` in user units (inherited).
    dash_offset: f64,
}

impl Default for Computed {
    fn default() -> Computed {
        Computed {
            stroke: Paint::None,
            fill: Paint::Color(Rgba([0, 0, 0, 255])),
            stroke_opacity: 1.0,
            fill_opacity: 1.0,
            color: Rgba([0, 0, 0, 255]),
            opacity: 1.0,
            hidden: false,
            stroke_width: 1.0,
            non_scaling: false,
            // SVG's initial values: butt caps, miter joins, a miter limit of 4.
            stroke_shape: StrokeShape {
                cap: Cap::Butt,
                join: Join::Miter,
                miter_limit: 4.0,
            },
            dasharray: None,
            dash_relative: false,
            dash_offset: 0.0,
        }
    }
}

/// `roxmltree`'s node as `simplecss` matches selectors against it.
#[derive(Clone, Copy)]
struct El<'a, 'i>(Node<'a, 'i>);

impl simplecss::Element for El<'_, '_> {
    fn parent_element(&self) -> Option<Self> {
        self.0.parent_element().map(El)
    }

    fn prev_sibling_element(&self) -> Option<Self> {
        self.0.prev_sibling_element().map(El)
    }

    fn has_local_name(&self, name: &str) -> bool {
        self.0.tag_name().name() == name
    }

    fn attribute_matches(&self, name: &str, op: simplecss::AttributeOperator<'_>) -> bool {
        self.0.attribute(name).is_some_and(|v| op.matches(v))
    }

    fn pseudo_class_matches(&self, class: simplecss::PseudoClass<'_>) -> bool {
        matches!(class, simplecss::PseudoClass::FirstChild)
            && self.0.prev_sibling_element().is_none()
    }
}

/// Elements drawn as nothing here, by name: each is counted in the warning.
const LEFT_OUT: &[&str] = &[
    "text",
    "image",
    "foreignObject",
    "filter",
    "mask",
    "pattern",
    "marker",
    "clipPath",
    "video",
    "audio",
    "canvas",
    "iframe",
];

/// Elements that draw nothing and hold nothing drawn (their content is reached by
/// reference, if at all).
const SILENT: &[&str] = &[
    "defs",
    "symbol",
    "style",
    "title",
    "desc",
    "metadata",
    "script",
    "linearGradient",
    "radialGradient",
    "stop",
];

struct Reader<'a, 'i> {
    file: &'a str,
    doc: &'a Document<'i>,
    sheet: Vec<simplecss::Rule<'a>>,
    ids: HashMap<&'a str, Node<'a, 'i>>,
    curves: Vec<SceneCurve>,
    left_out: BTreeMap<String, usize>,
    elements: u64,
    max_elements: u64,
    max_depth: u64,
    max_curves: u64,
    max_points: u64,
    /// The `<use>` elements being expanded (their positions), for cycles.
    using: Vec<usize>,
}

/// Reads SVG `text` (from `file`, for messages) as a scene of path curves.
///
/// # Errors
/// [`ImportError::Syntax`] for XML that does not parse, [`ImportError::Element`] for an
/// element whose geometry, reference or numbers are wrong (naming its line), and
/// [`ImportError::Limit`] past a documented limit.
pub fn read(text: &str, file: &str) -> Result<Imported, ImportError> {
    let limit = |l: limits::Limit| {
        l.value().map_err(|source| ImportError::Limit {
            file: file.to_owned(),
            source,
        })
    };
    let max_elements = limit(limits::IMPORT_ELEMENTS)?;
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        nodes_limit: u32::try_from(max_elements.saturating_mul(4)).unwrap_or(u32::MAX),
        ..roxmltree::ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, opts).map_err(|e| {
        let pos = e.pos();
        ImportError::Syntax {
            file: file.to_owned(),
            line: pos.row,
            column: pos.col,
            message: e.to_string(),
        }
    })?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(ImportError::Syntax {
            file: file.to_owned(),
            line: doc.text_pos_at(root.range().start).row,
            column: 1,
            message: format!(
                "the root element is <{}>, not <svg>: not an SVG file",
                root.tag_name().name()
            ),
        });
    }
    let mut reader = Reader {
        file,
        doc: &doc,
        sheet: Vec::new(),
        ids: HashMap::new(),
        curves: Vec::new(),
        left_out: BTreeMap::new(),
        elements: 0,
        max_elements,
        max_depth: limit(limits::IMPORT_DEPTH)?,
        max_curves: limit(limits::CURVES)?,
        max_points: limit(limits::POINTS)?,
        using: Vec::new(),
    };
    for n in doc.descendants().filter(Node::is_element) {
        if let Some(id) = n.attribute("id") {
            reader.ids.entry(id).or_insert(n);
        }
        if n.tag_name().name() == "style" {
            for t in n.children().filter_map(|c| c.text()) {
                reader.sheet.extend(simplecss::StyleSheet::parse(t).rules);
            }
        }
    }
    // Specificity order (stable: later rules of equal specificity win, as they apply
    // later).
    reader.sheet.sort_by_key(|r| r.selector.specificity());
    let flip = root_flip(&reader, root)?;
    reader.walk(root, flip, Computed::default(), 0)?;
    Ok(Imported::of_file(file, reader.curves, &reader.left_out))
}

/// The map from the root's user units to the scene: y flipped about the viewBox (or the
/// height), so that the picture is seen as a browser shows it, not mirrored.
fn root_flip(r: &Reader<'_, '_>, root: Node<'_, '_>) -> Result<DAffine2, ImportError> {
    let bottom = match root.attribute("viewBox") {
        Some(v) => {
            let nums: Vec<f64> = v
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|s| !s.is_empty())
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|_| r.element_error(root, format!("viewBox {v:?}: not four numbers")))?;
            match nums[..] {
                [_, y, _, h] if nums.iter().all(|x| x.is_finite()) && h >= 0.0 => y + h,
                _ => {
                    return Err(r.element_error(
                        root,
                        format!("viewBox {v:?}: four finite numbers, the height not negative"),
                    ));
                }
            }
        }
        None => r.length(root, "height", 0.0)?.unwrap_or(0.0),
    };
    Ok(DAffine2::from_cols_array(&[
        1.0, 0.0, 0.0, -1.0, 0.0, bottom,
    ]))
}

impl<'a, 'i> Reader<'a, 'i> {
    fn line(&self, n: Node<'_, '_>) -> u32 {
        self.doc.text_pos_at(n.range().start).row
    }

    fn element_error(&self, n: Node<'_, '_>, message: String) -> ImportError {
        ImportError::Element {
            file: self.file.to_owned(),
            line: self.line(n),
            element: n.tag_name().name().to_owned(),
            message,
        }
    }

    /// A length attribute in user units (`px` and unitless as they are; absolute units at
    /// 96 per inch; `em`/`ex` at 16 and 8; percentages of `reference`).
    fn length(
        &self,
        n: Node<'_, '_>,
        name: &str,
        reference: f64,
    ) -> Result<Option<f64>, ImportError> {
        let Some(v) = n.attribute(name) else {
            return Ok(None);
        };
        let l: svgtypes::Length = v
            .parse()
            .map_err(|e| self.element_error(n, format!("{name}={v:?}: {e}")))?;
        use svgtypes::LengthUnit as U;
        let k = match l.unit {
            U::None | U::Px => 1.0,
            U::In => 96.0,
            U::Cm => 96.0 / 2.54,
            U::Mm => 96.0 / 25.4,
            U::Pt => 96.0 / 72.0,
            U::Pc => 16.0,
            U::Em => 16.0,
            U::Ex => 8.0,
            U::Percent => reference / 100.0,
        };
        let x = l.number * k;
        if !x.is_finite() {
            return Err(self.element_error(n, format!("{name}={v:?}: not a finite length")));
        }
        Ok(Some(x))
    }

    fn number(&self, n: Node<'_, '_>, name: &str) -> Result<f64, ImportError> {
        Ok(self.length(n, name, 0.0)?.unwrap_or(0.0))
    }

    /// The element's own transform.
    fn transform(&self, n: Node<'_, '_>) -> Result<DAffine2, ImportError> {
        let Some(v) = n.attribute("transform") else {
            return Ok(DAffine2::IDENTITY);
        };
        let t: svgtypes::Transform = v
            .parse()
            .map_err(|e| self.element_error(n, format!("transform={v:?}: {e}")))?;
        let m = DAffine2::from_cols_array(&[t.a, t.b, t.c, t.d, t.e, t.f]);
        if !m.is_finite() {
            return Err(self.element_error(n, format!("transform={v:?}: not finite")));
        }
        Ok(m)
    }

    /// The declarations that apply to `n`, lowest priority first: presentation
    /// attributes, matching style rules (by specificity), the `style` attribute.
    fn declarations(&self, n: Node<'a, 'i>) -> Vec<(String, String)> {
        const PROPS: &[&str] = &[
            "stroke",
            "fill",
            "stroke-opacity",
            "fill-opacity",
            "opacity",
            "color",
            "display",
            "visibility",
            "stroke-width",
            "vector-effect",
            "stroke-linecap",
            "stroke-linejoin",
            "stroke-miterlimit",
            "stroke-dasharray",
            "stroke-dashoffset",
        ];
        let mut out: Vec<(String, String)> = PROPS
            .iter()
            .filter_map(|p| n.attribute(*p).map(|v| ((*p).to_owned(), v.to_owned())))
            .collect();
        for rule in &self.sheet {
            if rule.selector.matches(&El(n)) {
                out.extend(
                    rule.declarations
                        .iter()
                        .map(|d| (d.name.to_owned(), d.value.to_owned())),
                );
            }
        }
        if let Some(style) = n.attribute("style") {
            for d in simplecss::DeclarationTokenizer::from(style) {
                out.push((d.name.to_owned(), d.value.to_owned()));
            }
        }
        out
    }

    /// A paint value: `none`, a colour, `currentColor`, or a gradient's first stop.
    fn paint(&self, value: &str, current: Rgba, inherited: Paint) -> Paint {
        match svgtypes::Paint::from_str(value) {
            Ok(svgtypes::Paint::None) => Paint::None,
            Ok(svgtypes::Paint::Color(c)) => Paint::Color(Rgba([c.red, c.green, c.blue, c.alpha])),
            Ok(svgtypes::Paint::CurrentColor) => Paint::Color(current),
            Ok(svgtypes::Paint::FuncIRI(id, fallback)) => match self.first_stop(id) {
                Some(c) => Paint::Color(c),
                None => match fallback {
                    Some(svgtypes::PaintFallback::Color(c)) => {
                        Paint::Color(Rgba([c.red, c.green, c.blue, c.alpha]))
                    }
                    Some(svgtypes::PaintFallback::None) => Paint::None,
                    _ => Paint::Color(current),
                },
            },
            _ => inherited,
        }
    }

    /// A gradient's first stop colour (with its opacity), following `href` to the
    /// gradient that holds the stops.
    fn first_stop(&self, id: &str) -> Option<Rgba> {
        let mut node = *self.ids.get(id)?;
        for _ in 0..16 {
            if let Some(stop) = node.children().find(|c| c.has_tag_name("stop")) {
                let mut color = Rgba([0, 0, 0, 255]);
                let mut opacity: f64 = 1.0;
                for (k, v) in self.declarations(stop).into_iter().chain(
                    ["stop-color", "stop-opacity"].iter().filter_map(|p| {
                        stop.attribute(*p).map(|v| ((*p).to_owned(), v.to_owned()))
                    }),
                ) {
                    match k.as_str() {
                        "stop-color" => {
                            if let Ok(c) = v.parse::<svgtypes::Color>() {
                                color = Rgba([c.red, c.green, c.blue, c.alpha]);
                            }
                        }
                        "stop-opacity" => opacity = v.trim().parse().unwrap_or(1.0),
                        _ => {}
                    }
                }
                color.0[3] = (f64::from(color.0[3]) * opacity.clamp(0.0, 1.0)).round() as u8;
                return Some(color);
            }
            let href = node
                .attribute("href")
                .or_else(|| node.attribute(("http://www.w3.org/1999/xlink", "href")))?;
            node = *self.ids.get(href.strip_prefix('#')?)?;
        }
        None
    }

    fn computed(&self, n: Node<'a, 'i>, parent: &Computed) -> Computed {
        let mut c = parent.clone();
        c.hidden = false;
        c.non_scaling = false;
        let decls = self.declarations(n);
        // `color` first: `currentColor` in the others refers to it.
        for (k, v) in &decls {
            if k == "color"
                && let Ok(col) = v.parse::<svgtypes::Color>()
            {
                c.color = Rgba([col.red, col.green, col.blue, col.alpha]);
            }
        }
        for (k, v) in &decls {
            let v = v.trim();
            let num = |v: &str| v.parse::<f64>().ok().filter(|x| x.is_finite());
            match k.as_str() {
                "stroke" => c.stroke = self.paint(v, c.color, parent.stroke),
                "fill" => c.fill = self.paint(v, c.color, parent.fill),
                "stroke-opacity" => c.stroke_opacity = num(v).unwrap_or(1.0).clamp(0.0, 1.0),
                "fill-opacity" => c.fill_opacity = num(v).unwrap_or(1.0).clamp(0.0, 1.0),
                "opacity" => c.opacity = parent.opacity * num(v).unwrap_or(1.0).clamp(0.0, 1.0),
                "stroke-width" => {
                    // A length in user units (px, or a plain number); a negative or
                    // unreadable one is ignored, as CSS ignores an invalid declaration.
                    if let Ok(l) = v.parse::<svgtypes::Length>()
                        && matches!(
                            l.unit,
                            svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px
                        )
                        && l.number.is_finite()
                        && l.number >= 0.0
                    {
                        c.stroke_width = l.number;
                    }
                }
                "vector-effect" => c.non_scaling = v == "non-scaling-stroke",
                "stroke-linecap" => match v {
                    "butt" => c.stroke_shape.cap = Cap::Butt,
                    "round" => c.stroke_shape.cap = Cap::Round,
                    "square" => c.stroke_shape.cap = Cap::Square,
                    _ => {}
                },
                // SVG 2's `miter-clip` and `arcs` are not read (as browsers that do not
                // draw them): the declaration is ignored.
                "stroke-linejoin" => match v {
                    "miter" => c.stroke_shape.join = Join::Miter,
                    "round" => c.stroke_shape.join = Join::Round,
                    "bevel" => c.stroke_shape.join = Join::Bevel,
                    _ => {}
                },
                "stroke-miterlimit" => {
                    // At least 1 (a smaller one is invalid); past the drawable maximum
                    // the spike differs only where the stroke turns back by less than
                    // 0.12°, and is drawn at the maximum.
                    if let Some(m) = num(v).filter(|m| *m >= 1.0) {
                        c.stroke_shape.miter_limit = m.min(MAX_MITER_LIMIT);
                    }
                }
                "stroke-dasharray" => match dash::parse_dasharray(v) {
                    Some(dash::DashArray::Solid) => {
                        c.dasharray = None;
                        c.dash_relative = false;
                    }
                    Some(dash::DashArray::Lengths(l)) => {
                        c.dasharray = Some(l.into());
                        c.dash_relative = false;
                    }
                    Some(dash::DashArray::Relative) => {
                        c.dasharray = None;
                        c.dash_relative = true;
                    }
                    None => {}
                },
                "stroke-dashoffset" => {
                    if let Ok(l) = v.parse::<svgtypes::Length>()
                        && matches!(
                            l.unit,
                            svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px
                        )
                        && l.number.is_finite()
                    {
                        c.dash_offset = l.number;
                    }
                }
                "display" => c.hidden |= v == "none",
                "visibility" => c.hidden |= v == "hidden" || v == "collapse",
                _ => {}
            }
        }
        c
    }

    fn count(&mut self, n: Node<'_, '_>) -> Result<(), ImportError> {
        self.elements += 1;
        if self.elements > self.max_elements {
            let message = limits::IMPORT_ELEMENTS
                .check(self.elements)
                .err()
                .map_or_else(|| "too many elements".to_owned(), |e| e.to_string());
            return Err(self.element_error(n, message));
        }
        Ok(())
    }

    fn walk(
        &mut self,
        n: Node<'a, 'i>,
        parent_map: DAffine2,
        parent: Computed,
        depth: u64,
    ) -> Result<(), ImportError> {
        if depth > self.max_depth {
            return Err(self.element_error(
                n,
                limits::IMPORT_DEPTH
                    .check(depth)
                    .err()
                    .map_or_else(|| "nested too deep".to_owned(), |e| e.to_string()),
            ));
        }
        self.count(n)?;
        let tag = n.tag_name().name();
        if SILENT.contains(&tag) {
            return Ok(());
        }
        if LEFT_OUT.contains(&tag) {
            *self.left_out.entry(format!("<{tag}>")).or_default() += 1;
            return Ok(());
        }
        let style = self.computed(n, &parent);
        if style.hidden {
            return Ok(());
        }
        if n.attribute("filter").is_some() {
            *self
                .left_out
                .entry("filter effects".to_owned())
                .or_default() += 1;
        }
        let map = parent_map * self.transform(n)?;
        match tag {
            "svg" | "g" | "a" | "switch" => {
                let map = if tag == "svg" && depth > 0 {
                    let (x, y) = (self.number(n, "x")?, self.number(n, "y")?);
                    map * DAffine2::from_translation(DVec2::new(x, y))
                } else {
                    map
                };
                for c in n.children().filter(Node::is_element) {
                    self.walk(c, map, style.clone(), depth + 1)?;
                }
            }
            "use" => self.expand_use(n, map, style, depth)?,
            "path" | "line" | "polyline" | "polygon" | "rect" | "circle" | "ellipse" => {
                let subpaths = self.shape(n)?;
                self.emit(n, &subpaths, map, style)?;
            }
            other => {
                *self.left_out.entry(format!("<{other}>")).or_default() += 1;
            }
        }
        Ok(())
    }

    fn expand_use(
        &mut self,
        n: Node<'a, 'i>,
        map: DAffine2,
        style: Computed,
        depth: u64,
    ) -> Result<(), ImportError> {
        let href = n
            .attribute("href")
            .or_else(|| n.attribute(("http://www.w3.org/1999/xlink", "href")))
            .ok_or_else(|| self.element_error(n, "no href".to_owned()))?;
        let id = href.strip_prefix('#').ok_or_else(|| {
            self.element_error(
                n,
                format!("href {href:?}: only references inside the file (#id) are read"),
            )
        })?;
        let target = *self.ids.get(id).ok_or_else(|| {
            self.element_error(n, format!("href {href:?}: no element has id {id:?}"))
        })?;
        let at = n.range().start;
        if self.using.contains(&at) || target.ancestors().any(|a| a == n) {
            return Err(self.element_error(
                n,
                format!("href {href:?}: a reference cycle (the element refers, through <use>, to itself)"),
            ));
        }
        let (x, y) = (self.number(n, "x")?, self.number(n, "y")?);
        let map = map * DAffine2::from_translation(DVec2::new(x, y));
        self.using.push(at);
        let result = if target.has_tag_name("symbol") {
            target
                .children()
                .filter(Node::is_element)
                .try_for_each(|c| self.walk(c, map, style.clone(), depth + 1))
        } else {
            self.walk(target, map, style, depth + 1)
        };
        self.using.pop();
        result
    }

    /// The element's geometry in its own user units.
    fn shape(&self, n: Node<'a, 'i>) -> Result<Vec<Subpath>, ImportError> {
        let num = |name: &str| self.number(n, name);
        let positive = |name: &str, v: f64| {
            if v < 0.0 {
                Err(self.element_error(n, format!("{name} = {v}: negative")))
            } else {
                Ok(v)
            }
        };
        let points = |name: &str| -> Result<Vec<DVec2>, ImportError> {
            let text = n.attribute(name).unwrap_or("");
            let nums: Vec<f64> = svgtypes::NumberListParser::from(text)
                .collect::<Result<_, _>>()
                .map_err(|e| self.element_error(n, format!("{name}: {e}")))?;
            if nums.iter().any(|x| !x.is_finite()) {
                return Err(self.element_error(n, format!("{name}: a number that is not finite")));
            }
            // An odd count drops the last number, as SVG says.
            Ok(nums
                .chunks_exact(2)
                .map(|c| DVec2::new(c[0], c[1]))
                .collect())
        };
        Ok(match n.tag_name().name() {
            "path" => {
                path_data(n.attribute("d").unwrap_or("")).map_err(|e| self.element_error(n, e.0))?
            }
            "line" => {
                let (a, b) = (
                    DVec2::new(num("x1")?, num("y1")?),
                    DVec2::new(num("x2")?, num("y2")?),
                );
                geometry::polyline(&[a, b], false).into_iter().collect()
            }
            "polyline" => geometry::polyline(&points("points")?, false)
                .into_iter()
                .collect(),
            "polygon" => geometry::polyline(&points("points")?, true)
                .into_iter()
                .collect(),
            "rect" => {
                let (x, y) = (num("x")?, num("y")?);
                let (w, h) = (
                    positive("width", num("width")?)?,
                    positive("height", num("height")?)?,
                );
                if w == 0.0 || h == 0.0 {
                    return Ok(Vec::new());
                }
                let rx = self
                    .length(n, "rx", w)?
                    .map(|v| positive("rx", v))
                    .transpose()?;
                let ry = self
                    .length(n, "ry", h)?
                    .map(|v| positive("ry", v))
                    .transpose()?;
                let (rx, ry) = match (rx, ry) {
                    (None, None) => (0.0, 0.0),
                    (Some(r), None) | (None, Some(r)) => (r, r),
                    (Some(a), Some(b)) => (a, b),
                };
                vec![geometry::rect(x, y, w, h, rx.min(0.5 * w), ry.min(0.5 * h))]
            }
            "circle" => {
                let r = positive("r", num("r")?)?;
                if r == 0.0 {
                    return Ok(Vec::new());
                }
                vec![geometry::ellipse(DVec2::new(num("cx")?, num("cy")?), r, r)]
            }
            "ellipse" => {
                let (rx, ry) = (positive("rx", num("rx")?)?, positive("ry", num("ry")?)?);
                if rx == 0.0 || ry == 0.0 {
                    return Ok(Vec::new());
                }
                vec![geometry::ellipse(
                    DVec2::new(num("cx")?, num("cy")?),
                    rx,
                    ry,
                )]
            }
            _ => Vec::new(),
        })
    }

    /// One path curve per subpath, in the scene's coordinates, coloured by its stroke or
    /// (without one) its fill.
    fn emit(
        &mut self,
        n: Node<'a, 'i>,
        subpaths: &[Subpath],
        map: DAffine2,
        style: Computed,
    ) -> Result<(), ImportError> {
        // A stroke of width 0 is not painted.
        let stroke = if style.stroke_width > 0.0 {
            style.stroke
        } else {
            Paint::None
        };
        let stroked = matches!(stroke, Paint::Color(_));
        let color = match (stroke, style.fill) {
            (Paint::Color(c), _) => Some((c, style.stroke_opacity)),
            (Paint::None, Paint::Color(c)) => Some((c, style.fill_opacity)),
            (Paint::None, Paint::None) => None,
        };
        let Some((Rgba(mut rgba), opacity)) = color else {
            // Neither stroked nor filled: not seen in a browser.
            return Ok(());
        };
        rgba[3] = (f64::from(rgba[3]) * opacity * style.opacity).round() as u8;
        let base = match n.attribute("id") {
            Some(id) => format!("{}#{id}", n.tag_name().name()),
            None => format!("{} (line {})", n.tag_name().name(), self.line(n)),
        };
        let many = subpaths.len() > 1;
        for (k, sub) in subpaths.iter().enumerate() {
            if sub.segments.is_empty() {
                continue;
            }
            if self.curves.len() as u64 >= self.max_curves {
                return Err(self.element_error(
                    n,
                    limits::CURVES
                        .check(self.curves.len() as u64 + 1)
                        .err()
                        .map_or_else(String::new, |e| e.to_string()),
                ));
            }
            let count: u64 = sub.segments.iter().map(|s| s.points.len() as u64).sum();
            if count > self.max_points {
                return Err(self.element_error(
                    n,
                    limits::POINTS
                        .check(count)
                        .err()
                        .map_or_else(String::new, |e| e.to_string()),
                ));
            }
            // A dashed stroke is cut into its dashes in the element's user units (where
            // SVG measures them), then each is mapped; a solid one is the subpath.
            let dashes = match (&style.dasharray, stroked) {
                (Some(lengths), true) => Some(dash::Dashes::new(lengths, style.dash_offset)),
                _ => None,
            };
            let dashed = dashes.is_some();
            let paths: Vec<Path> = match dashes {
                None => {
                    let segments = sub.segments.iter().map(|s| s.mapped(map)).collect();
                    vec![
                        Path::try_new(segments, sub.closed)
                            .map_err(|e| self.element_error(n, format!("subpath {k}: {e}")))?,
                    ]
                }
                Some(dashes) => {
                    let segments = sub
                        .segments
                        .iter()
                        .map(|s| s.mapped(DAffine2::IDENTITY))
                        .collect();
                    let user = Path::try_new(segments, sub.closed)
                        .map_err(|e| self.element_error(n, format!("subpath {k}: {e}")))?;
                    let budget = self.max_curves - self.curves.len() as u64;
                    let cut = dashes
                        .cut(&user, budget)
                        .map_err(|e| self.element_error(n, format!("subpath {k}: {e}")))?;
                    cut.iter()
                        .map(|d| {
                            let mapped = d.segments().iter().map(|s| map_segment(s, map)).collect();
                            Path::try_new(mapped, false)
                                .map_err(|e| self.element_error(n, format!("subpath {k}: {e}")))
                        })
                        .collect::<Result<_, _>>()?
                }
            };
            if style.dash_relative && stroked {
                *self
                    .left_out
                    .entry("stroke-dasharray in em, ex or % (drawn solid)".into())
                    .or_default() += 1;
            }
            for (j, path) in paths.into_iter().enumerate() {
                let index = self.curves.len();
                let mut s = Style::default_for(index);
                s.color = Color::from_rgba8(rgba);
                s.show_polygon = false;
                s.show_points = false;
                if stroked {
                    s.stroke = style.stroke_shape;
                    // The stroke's width in user units, scaled by the transform as the
                    // geometry is (by the square root of its area scale), so that it zooms
                    // with the picture; with non-scaling-stroke, pixels.
                    let scale = map.matrix2.determinant().abs().sqrt();
                    let w = if style.non_scaling {
                        style.stroke_width
                    } else {
                        style.stroke_width * scale
                    };
                    if style.non_scaling && w > 1000.0 {
                        return Err(self.element_error(
                            n,
                            format!(
                                "a non-scaling stroke-width of {w} px is over the maximum of 1000"
                            ),
                        ));
                    }
                    if (w as f32).is_finite() && w as f32 > 0.0 {
                        s.width = w as f32;
                        s.width_in_scene = !style.non_scaling;
                    }
                } else {
                    // A fill alone is drawn as its outline: a thin line in pixels.
                    s.width = 1.0;
                }
                let name = if many {
                    format!("{base}, subpath {k}")
                } else {
                    base.clone()
                };
                self.curves.push(SceneCurve {
                    name: Some(if dashed {
                        format!("{name}, dash {j}")
                    } else {
                        name
                    }),
                    curve: Curve::Path(path),
                    style: s,
                });
            }
        }
        Ok(())
    }
}

/// A path segment in the plane `z = 0` mapped by `m`.
fn map_segment(s: &PathSegment, m: DAffine2) -> PathSegment {
    PathSegment {
        points: s
            .points
            .iter()
            .map(|p| m.transform_point2(p.truncate()).extend(0.0))
            .collect(),
        weights: s.weights.clone(),
    }
}
