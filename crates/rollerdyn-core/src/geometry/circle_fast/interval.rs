//! Interval bounds of the fast path ([`super`], step 2 of its search): the sinusoids
//! X, Y, z of the smaller circle's angle and closed intervals with the arithmetic the
//! bounds on F and F'' need.

use super::SLACK;

/// g(t) = offset + cos·cos t + sin·sin t.
#[derive(Debug, Clone, Copy)]
pub(super) struct Sinusoid {
    pub(super) offset: f64,
    pub(super) cos: f64,
    pub(super) sin: f64,
}

impl Sinusoid {
    #[inline]
    pub(super) fn at(&self, c: f64, s: f64) -> f64 {
        self.offset + self.cos * c + self.sin * s
    }

    #[inline]
    pub(super) fn slope(&self, c: f64, s: f64) -> f64 {
        self.sin * c - self.cos * s
    }
}

/// A closed interval.
#[derive(Debug, Clone, Copy)]
pub(super) struct Iv {
    pub(super) lo: f64,
    pub(super) hi: f64,
}

impl Iv {
    /// Bounds of a sinusoid on an arc from its values at the ends (module docs, step 2).
    #[inline]
    pub(super) fn sinusoid(ga: f64, gb: f64, offset: f64, bulge: f64) -> Iv {
        let (ea, eb) = (ga - offset, gb - offset);
        let m = 0.5 * (ea + eb) * bulge;
        Iv {
            lo: offset + ea.min(eb) + m.min(0.0) - SLACK,
            hi: offset + ea.max(eb) + m.max(0.0) + SLACK,
        }
    }

    #[inline]
    pub(super) fn add(self, o: Iv) -> Iv {
        Iv {
            lo: self.lo + o.lo,
            hi: self.hi + o.hi,
        }
    }

    #[inline]
    pub(super) fn mul(self, o: Iv) -> Iv {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        Iv {
            lo: p[0].min(p[1]).min(p[2]).min(p[3]),
            hi: p[0].max(p[1]).max(p[2]).max(p[3]),
        }
    }

    #[inline]
    pub(super) fn sq(self) -> Iv {
        let (a, b) = (self.lo * self.lo, self.hi * self.hi);
        if self.lo >= 0.0 {
            Iv { lo: a, hi: b }
        } else if self.hi <= 0.0 {
            Iv { lo: b, hi: a }
        } else {
            Iv {
                lo: 0.0,
                hi: a.max(b),
            }
        }
    }

    /// −(self − offset).
    #[inline]
    pub(super) fn reflect(self, offset: f64) -> Iv {
        Iv {
            lo: offset - self.hi,
            hi: offset - self.lo,
        }
    }

    #[inline]
    pub(super) fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
}
