//! Double-double arithmetic for the references: an unevaluated sum
//! `hi + lo`, `|lo| ≤ ulp(hi)/2`, about 106 bits (Dekker; Hida, Li and
//! Bailey's QD algorithms).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

/// `a + b = hi + lo` exactly (Knuth's TwoSum).
pub fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    Dd {
        hi: s,
        lo: (a - av) + (b - bv),
    }
}

/// `a + b = hi + lo` exactly when `|a| ≥ |b|` (Dekker's FastTwoSum).
pub fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

/// `a · b = hi + lo` exactly (FMA; speed does not matter here).
pub fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    Dd {
        hi: p,
        lo: a.mul_add(b, -p),
    }
}

impl Dd {
    pub const fn new(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }
    /// π to double-double precision.
    pub const PI: Dd = Dd {
        hi: core::f64::consts::PI,
        lo: 1.224_646_799_147_353_2e-16,
    };
    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.hi, o.hi);
        let t = two_sum(self.lo, o.lo);
        let s = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(s.hi, s.lo + t.lo)
    }
    pub fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
    pub fn sub(self, o: Dd) -> Dd {
        self.add(o.neg())
    }
    pub fn mul(self, o: Dd) -> Dd {
        let p = two_prod(self.hi, o.hi);
        quick_two_sum(p.hi, p.lo + (self.hi * o.lo + self.lo * o.hi))
    }
    pub fn div(self, o: Dd) -> Dd {
        // Long division: two correction steps.
        let q1 = self.hi / o.hi;
        let r = self.sub(o.mul(Dd::new(q1)));
        let q2 = r.hi / o.hi;
        let r = r.sub(o.mul(Dd::new(q2)));
        let q3 = r.hi / o.hi;
        quick_two_sum(q1, q2).add(Dd::new(q3))
    }
    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::new(0.0);
        }
        // One Newton step from the f64 root doubles the digits.
        let x = self.hi.sqrt();
        let r = self.sub(two_prod(x, x));
        quick_two_sum(x, r.hi / (2.0 * x))
    }
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
}
