//! How the library's results are written, shared by the commands: μ as text, why a march
//! stopped, the solver's work counters, the shapes file.

use crate::error::Res;
use crate::table::{csv_line, num, opt, AtomicFile};
use serde::ser::{SerializeMap, SerializeStruct, Serializer};
use serde::Serialize;
use vibrissa::{ShapePoint, StopReason};

/// μ as written: `inf`/`-inf` at lift-off, where it is unbounded.
pub fn mu_text(mu: f64) -> String {
    if mu.is_infinite() {
        if mu > 0.0 { "inf" } else { "-inf" }.to_string()
    } else {
        num(mu)
    }
}

/// Why a scan or a drag stopped, as its CSV and JSON say it: the library's reason by name, where,
/// and in words.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Stop {
    /// `d_max`, `slip`, `lift_off`, `penetration`, `fold_in_d`, `solver_failure`, ...
    pub reason: String,
    /// where (last displacement)
    pub d: Option<f64>,
    /// in words
    pub detail: String,
}

impl From<&StopReason> for Stop {
    fn from(s: &StopReason) -> Stop {
        Stop {
            reason: s.name().into(),
            d: s.at(),
            detail: s.to_string(),
        }
    }
}

/// The solver's work counters written with a result: Newton iterations, right-hand-side
/// evaluations, factorizations (the library's statistics, of which these three).
pub struct Work<'a>(pub &'a bvp::Stats);

impl Serialize for Work<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Work", 3)?;
        st.serialize_field("newton_iters", &self.0.newton_iters)?;
        st.serialize_field("rhs_evals", &self.0.rhs_evals)?;
        st.serialize_field("factorizations", &self.0.factorizations)?;
        st.end()
    }
}

/// Write a shape CSV (columns s, x, y, phi, kappa, m) atomically.
pub fn write_shape(path: &std::path::Path, shape: &[ShapePoint]) -> Res<()> {
    let mut f = AtomicFile::create(path)?;
    csv_line(&mut f, &["s", "x", "y", "phi", "kappa", "m"])?;
    for p in shape {
        csv_line(&mut f, &[p.s, p.x, p.y, p.phi, p.kappa, p.m].map(num))?;
    }
    f.commit()
}

/// The shapes file of a scan or a drag (columns point, d, s, x, y, x_lab, phi, kappa, m, event;
/// `vibrissa plot` reads it): one `(d, event, samples)` per point; x_lab = x + d is the lab
/// frame (the foot started at 0, the tip stays put). A drag whose support turns (`turn`) has
/// `theta` for `d`, and x_lab = x (the foot held at 0).
pub fn write_shape_file<'a>(
    path: &std::path::Path,
    points: impl Iterator<Item = (f64, &'a str, &'a [ShapePoint])>,
    turn: bool,
) -> Res<()> {
    let mut f = AtomicFile::create(path)?;
    let d_col = if turn { "theta" } else { "d" };
    csv_line(
        &mut f,
        &[
            "point", d_col, "s", "x", "y", "x_lab", "phi", "kappa", "m", "event",
        ],
    )?;
    for (i, (d, event, sh)) in points.enumerate() {
        let xf = if turn { 0.0 } else { d };
        for q in sh {
            let mut r = vec![i.to_string()];
            r.extend([d, q.s, q.x, q.y, q.x + xf, q.phi, q.kappa, q.m].map(num));
            r.push(event.to_string());
            csv_line(&mut f, &r)?;
        }
    }
    f.commit()
}

/// One value of a one-row result, written as CSV text or as a JSON value.
pub enum Cell {
    /// a name (text)
    Name(&'static str),
    /// a number (empty in CSV when not finite)
    Num(f64),
    /// a friction ratio: `inf` in CSV where unbounded, as [`mu_text`]
    Mu(f64),
    /// a count
    Count(usize),
    /// a number or nothing
    Opt(Option<f64>),
    /// yes or no: 1/0 in CSV, true/false in JSON
    Flag(bool),
}

impl Cell {
    fn text(&self) -> String {
        match self {
            Cell::Name(s) => s.to_string(),
            Cell::Num(v) => num(*v),
            Cell::Mu(v) => mu_text(*v),
            Cell::Count(n) => n.to_string(),
            Cell::Opt(v) => opt(*v),
            Cell::Flag(b) => u8::from(*b).to_string(),
        }
    }
}

impl Serialize for Cell {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Cell::Name(v) => v.serialize(s),
            Cell::Num(v) | Cell::Mu(v) => v.serialize(s),
            Cell::Count(v) => v.serialize(s),
            Cell::Opt(v) => v.serialize(s),
            Cell::Flag(v) => v.serialize(s),
        }
    }
}

/// A result of one row, its columns named once: a CSV header and row, or a JSON object with
/// the same keys in the same order.
pub struct Row(pub Vec<(&'static str, Cell)>);

impl Row {
    /// The header line and the row.
    pub fn write_csv<W: std::io::Write>(&self, w: &mut W) -> Res<()> {
        let head: Vec<&str> = self.0.iter().map(|c| c.0).collect();
        let row: Vec<String> = self.0.iter().map(|c| c.1.text()).collect();
        csv_line(w, &head)?;
        csv_line(w, &row)
    }

    /// The row only (the next row of a table whose header [`Row::write_csv`] wrote).
    pub fn write_values<W: std::io::Write>(&self, w: &mut W) -> Res<()> {
        let row: Vec<String> = self.0.iter().map(|c| c.1.text()).collect();
        csv_line(w, &row)
    }
}

impl Serialize for Row {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}

/// Key-value pairs as a JSON object, in their order.
pub struct Object<'a>(pub &'a [(String, f64)]);

impl Serialize for Object<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}
