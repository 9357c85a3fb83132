//! Numbers on the command line: parsing every spelling of `f64` that Rust accepts, grid axes
//! (`a:b:n` ranges computed from integer steps, comma lists), shards, and short numbers in
//! messages that still have enough digits to show why a value is outside its range.
//!
//! Depends on `std` and the library's [`vibrissa::limits::digits`] only (the end-to-end tests
//! include it together with `cli.rs`).

use std::fmt::Write as _;
pub use vibrissa::limits::digits;

/// Parse a number as Rust's `f64` parser does (`-1e-3`, `-.5`, `+5E-1`, `inf`, `-infinity`),
/// after trimming spaces. The message names the text, not the flag (clap adds the flag).
pub fn parse_f64(s: &str) -> Result<f64, String> {
    let t = s.trim();
    t.parse::<f64>().map_err(|_| {
        if t.starts_with("--") {
            format!("'{t}' is not a number (a flag where a value was expected?)")
        } else {
            format!("'{t}' is not a number")
        }
    })
}

/// Parse a finite number (NaN and infinities are refused).
pub fn finite_f64(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{}' is not a finite number", s.trim()))
    }
}

/// Parse a number that may be `+inf` (meaning "no limit"); NaN and `-inf` are refused later by
/// the range check of the quantity, so that the message can state the range.
pub fn number_or_inf(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v.is_nan() {
        Err(format!("'{}' is not a number", s.trim()))
    } else {
        Ok(v)
    }
}

/// Parse a count (integer) in `[lo, hi]`, accepting a leading sign so that `-1` reaches this
/// check and is refused with the range rather than taken for a flag.
pub fn count(s: &str, lo: u64, hi: u64) -> Result<u32, String> {
    let t = s.trim();
    let v: i128 = t
        .strip_prefix('+')
        .unwrap_or(t)
        .parse()
        .map_err(|_| format!("'{t}' is not a whole number"))?;
    if v < lo as i128 || v > hi as i128 {
        return Err(format!("{t} is outside the valid range [{lo}, {hi}]"));
    }
    Ok(v as u32)
}

/// A grid axis of `vibrissa sweep`: its values (a list, or a range whose values are computed
/// when asked for, so that a 10^7-point range costs no memory and its size is known at once), and
/// the text they came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    values: Values,
    /// The text typed by the user.
    pub text: String,
}

#[derive(Clone, Debug, PartialEq)]
enum Values {
    /// a comma list (at least one value)
    List(Vec<f64>),
    /// `a:b:n`, `n >= 2`: `a + (b − a)·i/(n − 1)`, from the decimal digits typed when they parse
    Range {
        a: f64,
        b: f64,
        exact: Option<(Decimal, Decimal)>,
        n: u64,
    },
}

impl Axis {
    /// Number of values (never 0).
    pub fn len(&self) -> u64 {
        match &self.values {
            Values::List(v) => v.len() as u64,
            Values::Range { n, .. } => *n,
        }
    }

    /// The `i`-th value (`i < len()`).
    pub fn get(&self, i: u64) -> f64 {
        match &self.values {
            Values::List(v) => v[i as usize],
            Values::Range { a, b, exact, n } => {
                let last = n - 1;
                exact
                    .and_then(|(da, db)| lerp_exact(&da, &db, i, last))
                    .unwrap_or_else(|| {
                        if i == last {
                            *b
                        } else {
                            a + (b - a) * i as f64 / last as f64
                        }
                    })
            }
        }
    }

    /// The first value.
    pub fn first(&self) -> f64 {
        self.get(0)
    }

    /// The values a check against an interval needs to see: every value of a list, the two ends
    /// of a range (its other values lie between them: each is the correctly rounded value of a
    /// point between the ends, or their convex combination).
    pub fn extremes(&self) -> Vec<f64> {
        match &self.values {
            Values::List(v) => v.clone(),
            Values::Range { n, .. } => vec![self.get(0), self.get(n - 1)],
        }
    }

    /// The smallest and the largest value.
    pub fn min_max(&self) -> (f64, f64) {
        self.extremes()
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(*v), hi.max(*v))
            })
    }

    /// The first value that is not a whole number, if any. A range of whole ends has only whole
    /// values when its step is whole, that is when its second value is.
    pub fn first_fraction(&self) -> Option<f64> {
        let whole = |v: f64| v.fract() == 0.0;
        match &self.values {
            Values::List(v) => v.iter().copied().find(|v| !whole(*v)),
            Values::Range { n, .. } => [0, 1, n - 1]
                .into_iter()
                .map(|i| self.get(i))
                .find(|v| !whole(*v)),
        }
    }
}

/// Most points of one range `a:b:n`.
pub const MAX_AXIS_POINTS: u64 = 10_000_000;

/// Parse a grid axis: `a:b:n` (n points, both ends included) or a comma list `v1,v2,...` of
/// finite numbers.
///
/// Range points are `a + (b − a)·i/(n − 1)` computed exactly from the decimal digits typed and
/// rounded once to the nearest `f64`, so `0.6:0.95:8` gives `0.8`, not `0.7999999999999999`
/// (falls back to floating point for spellings that are not plain decimals). A range's values
/// are computed when asked for ([`Axis::get`]), not here.
pub fn parse_axis(s: &str) -> Result<Axis, String> {
    parse_axis_with(s, finite_f64)
}

/// [`parse_axis`], with `inf` allowed in a list (`--mu0 0.5,1,inf`: inf is "never slips").
pub fn parse_axis_or_inf(s: &str) -> Result<Axis, String> {
    parse_axis_with(s, number_or_inf)
}

fn parse_axis_with(s: &str, item: fn(&str) -> Result<f64, String>) -> Result<Axis, String> {
    let values = if s.contains(':') {
        let parts: Vec<&str> = s.split(':').collect();
        if parts.len() != 3 {
            return Err(format!(
                "'{s}' is not a range a:b:n (start, end, number of points) nor a comma list"
            ));
        }
        let (a, b) = (finite_f64(parts[0])?, finite_f64(parts[1])?);
        let n = parts[2].trim();
        let n: i128 = n
            .strip_prefix('+')
            .unwrap_or(n)
            .parse()
            .map_err(|_| format!("'{n}' is not a point count (the n of a:b:n)"))?;
        if n < 1 || n > MAX_AXIS_POINTS as i128 {
            return Err(format!(
                "point count {n} is outside the valid range [1, {MAX_AXIS_POINTS}]"
            ));
        }
        let n = n as u64;
        if n == 1 {
            if a != b {
                return Err(format!(
                    "a range of 1 point needs a = b (got {} and {}); write a single value",
                    parts[0].trim(),
                    parts[1].trim()
                ));
            }
            Values::List(vec![a])
        } else {
            Values::Range {
                a,
                b,
                exact: Decimal::parse(parts[0]).zip(Decimal::parse(parts[1])),
                n,
            }
        }
    } else {
        if s.trim().is_empty() {
            return Err("an empty list".into());
        }
        Values::List(s.split(',').map(item).collect::<Result<Vec<_>, _>>()?)
    };
    Ok(Axis {
        values,
        text: s.to_string(),
    })
}

/// A decimal number `m · 10^e` exactly as typed.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Decimal {
    m: i128,
    e: i32,
}

impl Decimal {
    /// `[+-]digits[.digits][(e|E)[+-]digits]` with at most 30 significant digits, else `None`.
    fn parse(s: &str) -> Option<Decimal> {
        let s = s.trim();
        let (neg, s) = match s.as_bytes().first()? {
            b'-' => (true, &s[1..]),
            b'+' => (false, &s[1..]),
            _ => (false, s),
        };
        let (mant, exp) = match s.find(['e', 'E']) {
            Some(i) => (&s[..i], s[i + 1..].parse::<i32>().ok()?),
            None => (s, 0),
        };
        let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
        if int.is_empty() && frac.is_empty() {
            return None;
        }
        if !int.bytes().chain(frac.bytes()).all(|c| c.is_ascii_digit()) {
            return None;
        }
        let digits = format!("{int}{frac}");
        let digits = digits.trim_start_matches('0');
        if digits.len() > 30 || exp.abs() > 400 {
            return None;
        }
        let m: i128 = if digits.is_empty() {
            0
        } else {
            digits.parse().ok()?
        };
        Some(Decimal {
            m: if neg { -m } else { m },
            e: exp - frac.len() as i32,
        })
    }
}

fn pow10(k: u32) -> Option<i128> {
    10i128.checked_pow(k)
}

/// `a + (b − a)·i/den`, exact, rounded once to the nearest `f64`; `None` on overflow.
fn lerp_exact(a: &Decimal, b: &Decimal, i: u64, den: u64) -> Option<f64> {
    let e = a.e.min(b.e);
    let am = a.m.checked_mul(pow10((a.e - e) as u32)?)?;
    let bm = b.m.checked_mul(pow10((b.e - e) as u32)?)?;
    // value = (am·(den − i) + bm·i) / den · 10^e
    let num = am
        .checked_mul((den - i) as i128)?
        .checked_add(bm.checked_mul(i as i128)?)?;
    Some(ratio_to_f64(num, den as i128, e))
}

/// The nearest `f64` to `num / den · 10^e` (`den > 0`): the quotient's decimal digits (40
/// significant, then a sticky digit when the division is not exact) parsed by Rust's correctly
/// rounded parser.
fn ratio_to_f64(num: i128, den: i128, e: i32) -> f64 {
    let neg = num < 0;
    let n = num.unsigned_abs();
    let d = den as u128;
    let mut s = String::new();
    if neg {
        s.push('-');
    }
    let q = n / d;
    let mut r = n % d;
    let _ = write!(s, "{q}");
    let mut sig = if q == 0 { 0 } else { s.len() - neg as usize };
    if r != 0 {
        s.push('.');
        while r != 0 && sig < 40 {
            // r < d ≤ 1e7, so r·10 cannot overflow
            r *= 10;
            let digit = r / d;
            r %= d;
            s.push((b'0' + digit as u8) as char);
            if digit != 0 || sig > 0 {
                sig += 1;
            }
        }
        if r != 0 {
            s.push('1');
        }
    }
    let _ = write!(s, "e{e}");
    s.parse().unwrap_or(f64::NAN)
}

/// Parse `K/N` (1-based shard K of N).
pub fn parse_shard(s: &str) -> Result<(u64, u64), String> {
    let bad = || format!("'{s}' is not K/N with 1 <= K <= N (e.g. 3/10)");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let k: i128 = k.trim().parse().map_err(|_| bad())?;
    let n: i128 = n.trim().parse().map_err(|_| bad())?;
    if n < 1 || k < 1 || k > n || n > u32::MAX as i128 {
        return Err(bad());
    }
    Ok((k as u64, n as u64))
}

/// A number for a message: short (6 significant digits), scientific outside [1e-4, 1e6), never
/// a 300-digit decimal; `short(1e300) = "1e300"`.
pub fn short(v: f64) -> String {
    digits(v, 6)
}

/// The shortest digits that read back as `v`, in the form of [`digits`] (`1e300`, `0.75`).
pub fn shortest(v: f64) -> String {
    let sci = format!("{v:e}");
    let mant = sci.split('e').next().unwrap_or("");
    let p = mant.chars().filter(|c| c.is_ascii_digit()).count();
    digits(v, p.max(1))
}

/// Rewrite every long decimal in a message (more than 20 characters, as Rust's `{}` prints
/// 1e300) in short form; other text is kept.
pub fn shorten_numbers(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len());
    let mut tok = String::new();
    let flush = |tok: &mut String, out: &mut String| {
        if tok.len() > 20 {
            if let Ok(v) = tok.parse::<f64>() {
                out.push_str(&shortest(v));
                tok.clear();
                return;
            }
        }
        out.push_str(tok);
        tok.clear();
    };
    for c in msg.chars() {
        if c.is_ascii_digit() || c == '.' || (c == '-' && tok.is_empty()) {
            tok.push(c);
        } else {
            flush(&mut tok, &mut out);
            out.push(c);
        }
    }
    flush(&mut tok, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use vibrissa::limits::digits_to_decide;

    #[test]
    fn every_spelling() {
        for (s, v) in [
            ("-1e-3", -1e-3),
            ("-.5", -0.5),
            ("-5e-1", -0.5),
            ("+.5E+0", 0.5),
            ("-0", 0.0),
            ("1.", 1.0),
        ] {
            assert_eq!(finite_f64(s), Ok(v), "{s}");
        }
        assert!(finite_f64("-inf").is_err());
        assert_eq!(number_or_inf("-inf"), Ok(f64::NEG_INFINITY));
        assert!(number_or_inf("nan").is_err());
    }

    fn values(s: &str) -> Vec<f64> {
        let a = parse_axis(s).unwrap();
        (0..a.len()).map(|i| a.get(i)).collect()
    }

    #[test]
    fn ranges_are_exact_decimals() {
        let v = values("0.6:0.95:8");
        // exact values 0.6 + 0.05 i, each the nearest double of its decimal
        let want = [0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95];
        assert_eq!(v, want);
        let v = values("0.05:1:20");
        assert_eq!(v[7], 0.4);
        assert_eq!(v[19], 1.0);
        let v = values("-0.1:0.1:3");
        assert_eq!(v, [-0.1, 0.0, 0.1]);
        // thirds: the nearest double of 1/3, 2/3
        let v = values("0:1:4");
        assert_eq!(v, [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0]);
        let v = values("-1e-3:1e-3:5");
        assert_eq!(v, [-1e-3, -5e-4, 0.0, 5e-4, 1e-3]);
        assert_eq!(values("-1,0,1"), [-1.0, 0.0, 1.0]);
        assert!(parse_axis("0.5:0.9").is_err());
        assert!(parse_axis("0.5:0.9:1").is_err());
        assert!(parse_axis("0:1:-3").is_err());
        assert!(parse_axis("").is_err());
    }

    #[test]
    fn a_range_is_computed_when_asked() {
        // 10^7 points: known size, values on demand, ends exact
        let a = parse_axis("0.5:0.9:10000000").unwrap();
        assert_eq!(a.len(), 10_000_000);
        assert_eq!(a.extremes(), [0.5, 0.9]);
        assert_eq!(a.get(5_000_000), 0.5 + 0.4 * 5e6 / 9_999_999.0);
        assert_eq!(a.min_max(), (0.5, 0.9));
        let d = parse_axis("0.9:0.5:3").unwrap();
        assert_eq!(d.min_max(), (0.5, 0.9));
        assert_eq!(parse_axis("3,-1,2").unwrap().min_max(), (-1.0, 3.0));
        // whole numbers: ends and step
        assert_eq!(parse_axis("11:201:20").unwrap().first_fraction(), None);
        assert_eq!(
            parse_axis("11:200:3").unwrap().first_fraction(),
            Some(105.5)
        );
        assert_eq!(parse_axis("11,21.5").unwrap().first_fraction(), Some(21.5));
        // inf only where allowed, and only in lists
        assert!(parse_axis("0.5,inf").is_err());
        assert_eq!(
            parse_axis_or_inf("0.5,inf").unwrap().extremes(),
            [0.5, f64::INFINITY]
        );
        assert!(parse_axis_or_inf("0.5:inf:3").is_err());
        assert!(parse_axis_or_inf("nan").is_err());
    }

    #[test]
    fn message_numbers() {
        assert_eq!(short(1e300), "1e300");
        assert_eq!(short(-1e-300), "-1e-300");
        assert_eq!(short(0.75), "0.75");
        assert_eq!(short(123456.0), "123456");
        assert_eq!(short(1234567.0), "1.23457e6");
        assert_eq!(short(0.001), "0.001");
        let low = 0.456_946_581_044_463_6;
        let p = digits_to_decide(0.456946581, &[low, 1.0]);
        assert_ne!(digits(0.456946581, p), digits(low, p));
        assert!(digits(low, p).starts_with("0.45694658104"));
        assert_eq!(
            shorten_numbers(&format!("x = {} ok", 1e300)),
            "x = 1e300 ok"
        );
        assert_eq!(shorten_numbers("d = 0.5, 12"), "d = 0.5, 12");
    }
}
