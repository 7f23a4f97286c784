//! A one-pass JSON cursor for the readers' fast path: objects, arrays, plain strings and
//! numbers, read and converted as the bytes go by.
//!
//! serde_json reads a number's digits to scan it and, with `float_roundtrip`, converts it
//! by a slow exact algorithm: 40 % of loading a scene went there. The cursor converts each
//! number as it scans it, exactly, to the bits serde_json gives: Clinger's fast path, else a
//! floating-point guess checked with integers, else core's correctly rounded `str::parse`.
//! It gives up, returning `None`, on anything a scene does not usually hold (an escape in a
//! string, `null`, `true`, a number beyond f64, nesting deeper than [`SKIP_DEPTH`]) and on
//! anything that is not JSON; the caller then reads the document with serde, which either
//! reads it the same way or names what is wrong. So the cursor only has to be right about
//! what it accepts (tested value for value against serde_json).

/// Where the reader is in the text.
pub(super) struct Cursor<'a> {
    text: &'a str,
    at: usize,
}

/// 10^0 to 10^22: the powers of ten that f64 holds exactly (Clinger's fast path).
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// 10^0 to 10^19: the powers of ten that a u64 holds.
const POWERS_OF_TEN: [u64; 20] = {
    let mut powers = [1u64; 20];
    let mut k = 1;
    while k < 20 {
        powers[k] = powers[k - 1] * 10;
        k += 1;
    }
    powers
};

/// Deepest nesting [`Cursor::skip`] follows (serde_json's own limit is 128).
const SKIP_DEPTH: usize = 64;

impl<'a> Cursor<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Cursor { text, at: 0 }
    }

    fn bytes(&self) -> &'a [u8] {
        self.text.as_bytes()
    }

    /// The next byte that is not JSON whitespace, not taken.
    pub(super) fn peek(&mut self) -> Option<u8> {
        let b = self.bytes();
        while let Some(&c) = b.get(self.at) {
            if !matches!(c, b' ' | b'\n' | b'\r' | b'\t') {
                return Some(c);
            }
            self.at += 1;
        }
        None
    }

    /// Takes `c`, after any whitespace.
    pub(super) fn eat(&mut self, c: u8) -> Option<()> {
        (self.peek()? == c).then(|| self.at += 1)
    }

    /// Whitespace, then the end of the text.
    pub(super) fn end(&mut self) -> Option<()> {
        self.peek().is_none().then_some(())
    }

    /// A string without escapes, as it stands in the text.
    pub(super) fn string(&mut self) -> Option<&'a str> {
        self.eat(b'"')?;
        let start = self.at;
        let rest = &self.bytes()[start..];
        let len = rest
            .iter()
            .position(|&c| c == b'"' || c == b'\\' || c < 0x20)?;
        if rest[len] != b'"' {
            return None;
        }
        self.at = start + len + 1;
        // The quotes are ASCII, so the slice between them is whole UTF-8.
        Some(&self.text[start..start + len])
    }

    /// A JSON number, as serde_json (with `float_roundtrip`) reads it into an f64.
    pub(super) fn number(&mut self) -> Option<f64> {
        self.peek()?;
        let b = self.bytes();
        let start = self.at;
        let negative = b[start] == b'-';
        // Integer part: 0, or a digit 1-9 and more digits.
        let int_start = start + usize::from(negative);
        let int_end = digits_end(b, int_start);
        let int = &b[int_start..int_end];
        if int.is_empty() || (int[0] == b'0' && int.len() > 1) {
            return None;
        }
        let mut i = int_end;
        let mut fraction: &[u8] = &[];
        if b.get(i) == Some(&b'.') {
            let end = digits_end(b, i + 1);
            fraction = &b[i + 1..end];
            if fraction.is_empty() {
                return None;
            }
            i = end;
        }
        let mut exponent: i64 = 0;
        if matches!(b.get(i), Some(b'e' | b'E')) {
            let sign = usize::from(matches!(b.get(i + 1), Some(b'-' | b'+')));
            let end = digits_end(b, i + 1 + sign);
            let digits = &b[i + 1 + sign..end];
            if digits.is_empty() {
                return None;
            }
            // Clamped: far before the clamp, core's parser takes the number over.
            exponent = digits
                .iter()
                .fold(0, |e, &d| (e * 10 + i64::from(d - b'0')).min(1 << 32));
            if b[i + 1] == b'-' {
                exponent = -exponent;
            }
            i = end;
        }
        // What follows is for the caller to take: a comma, a bracket, or it gives up.
        self.at = i;
        let power = exponent - fraction.len() as i64;
        // Leading zeros are not significant digits: 0.000123 has three.
        let (int, fraction) = if int == b"0" {
            let zeros = fraction.iter().take_while(|&&c| c == b'0').count();
            (&int[1..], &fraction[zeros..])
        } else {
            (int, fraction)
        };
        // At most 19 digits fit a u64.
        let exact = (int.len() + fraction.len() <= 19)
            .then(|| accumulate(accumulate(0, int), fraction))
            .and_then(|significand| scaled(significand, power));
        match exact {
            Some(value) => Some(if negative { -value } else { value }),
            // Core's parser, correctly rounded too; beyond f64 serde_json refuses.
            None => {
                let value: f64 = self.text[start..i].parse().ok()?;
                value.is_finite().then_some(value)
            }
        }
    }

    /// An array: `item` reads each element.
    pub(super) fn array(&mut self, mut item: impl FnMut(&mut Self) -> Option<()>) -> Option<()> {
        self.eat(b'[')?;
        if self.eat(b']').is_some() {
            return Some(());
        }
        loop {
            item(self)?;
            match self.peek()? {
                b',' => self.at += 1,
                b']' => {
                    self.at += 1;
                    return Some(());
                }
                _ => return None,
            }
        }
    }

    /// An object: `entry` reads the value of each key.
    pub(super) fn object(
        &mut self,
        mut entry: impl FnMut(&mut Self, &'a str) -> Option<()>,
    ) -> Option<()> {
        self.eat(b'{')?;
        if self.eat(b'}').is_some() {
            return Some(());
        }
        loop {
            let key = self.string()?;
            self.eat(b':')?;
            entry(self, key)?;
            match self.peek()? {
                b',' => self.at += 1,
                b'}' => {
                    self.at += 1;
                    return Some(());
                }
                _ => return None,
            }
        }
    }

    /// Any value the cursor reads, left unused (a key the record does not know).
    pub(super) fn skip(&mut self) -> Option<()> {
        self.skip_nested(SKIP_DEPTH)
    }

    fn skip_nested(&mut self, depth: usize) -> Option<()> {
        match self.peek()? {
            b'"' => self.string().map(drop),
            b'[' => self.array(|c| c.skip_nested(depth.checked_sub(1)?)),
            b'{' => self.object(|c, _| c.skip_nested(depth.checked_sub(1)?)),
            _ => self.number().map(drop),
        }
    }
}

/// Where the run of decimal digits from `i` ends: eight bytes at a time, without a branch
/// per byte.
#[inline(always)]
fn digits_end(b: &[u8], mut i: usize) -> usize {
    while let Some(eight) = b.get(i..).and_then(|rest| rest.first_chunk::<8>()) {
        let run = leading_digits(u64::from_le_bytes(*eight));
        i += run;
        if run < 8 {
            return i;
        }
    }
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    i
}

/// `significand` followed by the decimal `digits` (at most 19 in all), eight at a time.
#[inline(always)]
fn accumulate(mut significand: u64, mut digits: &[u8]) -> u64 {
    while let Some((eight, rest)) = digits.split_first_chunk::<8>() {
        significand = significand * 100_000_000 + eight_digits(u64::from_le_bytes(*eight));
        digits = rest;
    }
    for &d in digits {
        significand = significand * 10 + u64::from(d - b'0');
    }
    significand
}

/// How many of the eight bytes of `chunk` (the first in the low byte) are ASCII digits
/// before the first that is not.
#[inline(always)]
fn leading_digits(chunk: u64) -> usize {
    const HIGH_BITS: u64 = 0x8080_8080_8080_8080;
    // A digit becomes 0-9. Seven bits of each byte plus 0x76 stay within the byte and
    // reach its high bit from 0x0A on; a byte whose own high bit is set is no digit either.
    let offset = chunk ^ 0x3030_3030_3030_3030;
    let above_nine = (offset & !HIGH_BITS) + 0x7676_7676_7676_7676;
    let not_digit = (above_nine | offset) & HIGH_BITS;
    not_digit.trailing_zeros() as usize / 8
}

/// The f64 nearest to `significand` · 10^`power`, when an exact method gives it cheaply:
/// Clinger's fast path for a significand up to 2^53 and |power| ≤ 22 (an exact significand
/// and an exact power of ten give the correctly rounded result in one operation), else a
/// floating-point guess checked with integers ([`checked`]). `None` leaves the number to
/// core's parser.
#[inline(always)]
fn scaled(significand: u64, power: i64) -> Option<f64> {
    let k = power.unsigned_abs() as usize;
    if k > 22 {
        return None;
    }
    let scale = EXACT_POWERS_OF_TEN[k];
    let guess = if power < 0 {
        significand as f64 / scale
    } else {
        significand as f64 * scale
    };
    if significand <= 1 << 53 {
        return Some(guess);
    }
    checked(significand, power, guess)
}

/// `guess`, or its neighbour, if it is the f64 nearest to `significand` · 10^`power`
/// (|power| ≤ 19: every product below fits a u128), compared exactly with integers; `None`
/// for a tie or a guess further out. The guess is the exact number rounded twice, so it is
/// at most about an ulp away.
fn checked(significand: u64, power: i64, guess: f64) -> Option<f64> {
    if power.unsigned_abs() > 19 {
        return None;
    }
    let ten = u128::from(POWERS_OF_TEN[power.unsigned_abs() as usize]);
    let bits = guess.to_bits();
    let mut mantissa = u128::from(bits & ((1 << 52) - 1) | 1 << 52);
    // guess = mantissa · 2^e; the number and the guess in one integer unit, and an ulp of
    // the guess in it.
    let e = ((bits >> 52) & 0x7FF) as i32 - 1075;
    let (number, mut guessed, ulp) = match (power >= 0, e) {
        (true, 0..) => (u128::from(significand) * ten, mantissa << e, 1u128 << e),
        (false, ..=0) => (u128::from(significand) << -e, mantissa * ten, ten),
        _ => return None,
    };
    for _ in 0..2 {
        let twice_off = 2 * number.abs_diff(guessed);
        if twice_off < ulp {
            return Some(f64::from_bits(
                bits & !((1 << 52) - 1) | (mantissa as u64 & ((1 << 52) - 1)),
            ));
        }
        if twice_off == ulp {
            return None; // a tie: core's parser rounds it to even
        }
        // One ulp toward the number, within the same binade.
        if number > guessed {
            (mantissa, guessed) = (mantissa + 1, guessed + ulp);
        } else {
            (mantissa, guessed) = (mantissa - 1, guessed - ulp);
        }
        if !(1 << 52..1 << 53).contains(&mantissa) {
            return None;
        }
    }
    None
}

/// The value of eight ASCII digits read as a little-endian u64 (the first digit in the low
/// byte), in three multiplications instead of eight dependent steps (as in Lemire, "Number
/// parsing at a gigabyte per second", 2021).
#[inline(always)]
fn eight_digits(chunk: u64) -> u64 {
    const LOW_BYTES: u64 = 0x0000_00FF_0000_00FF;
    const TIMES_100_AND_10E6: u64 = 100 + (1_000_000 << 32);
    const TIMES_1_AND_10E4: u64 = 1 + (10_000 << 32);
    let v = chunk - 0x3030_3030_3030_3030; // digits 0-9 in each byte
    let v = v.wrapping_mul(10) + (v >> 8); // pairs: 10·d0 + d1 in every other byte
    let hi = (v & LOW_BYTES).wrapping_mul(TIMES_100_AND_10E6);
    let lo = ((v >> 16) & LOW_BYTES).wrapping_mul(TIMES_1_AND_10E4);
    (hi.wrapping_add(lo) >> 32) & 0xFFFF_FFFF
}

/// Fills an empty slot with a value read: a key given twice is for serde to refuse.
pub(super) fn once<T>(slot: &mut Option<T>, value: Option<T>) -> Option<()> {
    if slot.is_some() {
        return None;
    }
    *slot = Some(value?);
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Option<f64> {
        let mut c = Cursor::new(text);
        let v = c.number()?;
        c.end()?;
        Some(v)
    }

    /// Every number the cursor accepts has serde_json's bits; what it refuses, serde_json
    /// reads or refuses itself (the slow path then does).
    fn agrees(text: &str) {
        let serde: Result<f64, _> = serde_json::from_str(text);
        match (read(text), serde) {
            (Some(v), Ok(s)) => assert_eq!(v.to_bits(), s.to_bits(), "{text}: {v} vs {s}"),
            (Some(v), Err(e)) => panic!("{text}: cursor {v}, serde_json refuses: {e}"),
            (None, _) => {}
        }
    }

    /// Numbers where readers go wrong: signs, zeros, integers past 2^53 and 2^64, the ends
    /// of f64's range and subnormals, halfway cases, and texts that are not JSON numbers.
    const FIXED: &[&str] = &[
        "0",
        "-0",
        "0.0",
        "-0.0",
        "1",
        "-1",
        "0.1",
        "0.3",
        "1e22",
        "1e23",
        "9007199254740992",
        "9007199254740993",
        "18446744073709551615",
        "18446744073709551616",
        "123456789012345678901234567890",
        "1.7976931348623157e308",
        "1.7976931348623159e308",
        "1e400",
        "-1e400",
        "2.2250738585072014e-308",
        "4.9e-324",
        "2e-324",
        "1e-400",
        "0e999999999999",
        "1E+2",
        "1e-2",
        "1.0e+0",
        "-1.9764985380136277",
        "0.2563606476142897",
        "0.1000000000000000055511151231257827",
        "2.4703282292062327e-324",
        "2.4703282292062328e-324",
        // Exact ties between two f64 (2^52 + k + 1/2, ulp 1) with significands above
        // 2^53: even wins, whichever side the floating-point guess falls on.
        "4503599627370496.5",
        "4503599627370497.5",
        "4503599627370498.5",
        "-4503599627370499.5",
        "45035996273704965e-1",
        "0.45035996273704975e16",
        "00",
        "01",
        "1.",
        ".5",
        "+1",
        "-",
        "1e",
        "1e+",
        "--1",
        "1.5x",
        "Infinity",
        "NaN",
    ];

    #[test]
    fn numbers_have_serde_json_bits() {
        for t in FIXED {
            agrees(t);
        }
        // Shortest round-trip texts (as the writers write them), and other spellings.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..100_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = f64::from_bits(state);
            if !v.is_finite() {
                continue;
            }
            agrees(&serde_json::to_string(&v).unwrap());
            agrees(&format!("{v:e}"));
            agrees(&format!("{:.3}", v % 1e6));
            agrees(&format!("{}", (state >> 11) as i64 - (1 << 52)));
            agrees(&format!("{}e{}", state % 100_000, (state >> 40) % 40));
            agrees(&format!(
                "-{}.{:05}e-{}",
                state % 1000,
                state % 99_991,
                (state >> 50) % 30
            ));
        }
    }

    #[test]
    fn values_in_objects_and_arrays() {
        assert_eq!(eight_digits(u64::from_le_bytes(*b"12345678")), 12_345_678);
        let run = |s: &[u8; 8]| leading_digits(u64::from_le_bytes(*s));
        assert_eq!(
            [run(b"09876543"), run(b"0987654:"), run(b"/9876543")],
            [8, 7, 0]
        );
        assert_eq!(
            [
                run(b"123\xb0\xb9567"),
                run(b"12 45678"),
                run(b"1234567\xff")
            ],
            [3, 2, 7]
        );
        for byte in 0..=255u8 {
            let chunk = u64::from_le_bytes([b'5', byte, b'1', b'2', b'3', b'4', b'5', b'6']);
            assert_eq!(
                leading_digits(chunk),
                if byte.is_ascii_digit() { 8 } else { 1 }
            );
        }
        assert_eq!(digits_end(b"1234567890123456789x", 0), 19);
        assert_eq!(digits_end(b"12x", 0), 2);
        assert_eq!(accumulate(7, b"0123456789"), 70_123_456_789);
        assert_eq!(read("1.5"), Some(1.5));
        assert_eq!(read(" -2 "), Some(-2.0));
        assert_eq!(read("1e400"), None);
        assert_eq!(read("01"), None);
        let mut c = Cursor::new(r#"{"a": [1, 2.5], "b": "x"}"#);
        let (mut a, mut b) = (Vec::new(), None);
        c.object(|c, key| match key {
            "a" => c.array(|c| {
                a.push(c.number()?);
                Some(())
            }),
            "b" => once(&mut b, c.string()),
            _ => None,
        })
        .unwrap();
        assert_eq!((a, b), (vec![1.0, 2.5], Some("x")));
        let numbers = |text: &str| {
            let mut c = Cursor::new(text);
            c.object(|c, _| c.array(|c| c.number().map(drop)))?;
            c.end()
        };
        assert_eq!(numbers(r#"{"a": [1, 2], "b": []}"#), Some(()));
        for bad in [
            r#"{"a" [1]}"#,
            r#"{"a\n": [1]}"#,
            r#"{"a": [1 2]}"#,
            r#"{"a": [1,]}"#,
            r#"{"a": [1],}"#,
            r#"{"a": [1]} x"#,
            r#"{"a": [1.5x]}"#,
            r#"{"a": [null]}"#,
            r#"{"a": [1]"#,
        ] {
            assert_eq!(numbers(bad), None, "{bad}");
        }
        let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
        assert_eq!(
            Cursor::new(&deep).skip(),
            None,
            "nesting gives up, never overflows"
        );
        assert_eq!(
            Cursor::new(r#"{"k": [1, "s", {"m": []}]}"#).skip(),
            Some(())
        );
    }
}
