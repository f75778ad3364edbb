//! An edge's cover by the spans its search has found so far.

/// The cover of an edge by the spans its search has found so far:
/// `[0, reach]` is covered, and the spans not within it are kept apart
/// (`pending`, which [`add_uncovered`](super::sum::add_uncovered) then takes with `(0, reach)`: the
/// same pieces as from every span, since `reach` is the largest end of the
/// spans it stands for). Each span that extends `reach` takes in the
/// pending spans it reaches, so the search ends at the span that completes
/// the cover. Past [`Cover::TRACKED`] spans, the pending ones are taken in
/// only when the number of spans is a power of two, which keeps an edge
/// with thousands of spans `O(m log m)`.
#[derive(Debug, Default)]
pub(super) struct Cover {
    pub(super) reach: f64,
    spans: usize,
}

impl Cover {
    /// The most spans of an edge followed span by span (ours, chosen by
    /// measurement: see benches/README.md § The union's constants and its
    /// two copies of the loop).
    pub(super) const TRACKED: usize = 128;

    /// Takes `span` (pending spans in `pending`); whether the edge is now
    /// covered whole. Kept out of the search's loop, which most candidates
    /// leave without a span.
    #[inline(never)]
    pub(super) fn add(&mut self, span: (f64, f64), pending: &mut Vec<(f64, f64)>) -> bool {
        self.spans += 1;
        if span.0 <= self.reach {
            self.reach = self.reach.max(span.1);
            if self.spans <= Cover::TRACKED {
                self.take_in(pending);
            }
        } else {
            pending.push(span);
        }
        if self.spans > Cover::TRACKED && self.spans.is_power_of_two() {
            self.take_in_sorted(pending);
        }
        self.reach >= 1.0
    }

    /// Takes in every pending span that starts within `[0, reach]`, until
    /// none does: up to four passes in their order, then (a longer chain in
    /// reverse order) one after sorting them.
    fn take_in(&mut self, pending: &mut Vec<(f64, f64)>) {
        for _ in 0..4 {
            let before = pending.len();
            let mut k = 0;
            while k < pending.len() {
                let (s, e) = pending[k];
                if s <= self.reach {
                    self.reach = self.reach.max(e);
                    pending.swap_remove(k);
                } else {
                    k += 1;
                }
            }
            if pending.len() == before {
                return;
            }
        }
        self.take_in_sorted(pending);
    }

    /// [`Cover::take_in`] by sorting the pending spans: `O(m log m)`.
    fn take_in_sorted(&mut self, pending: &mut Vec<(f64, f64)>) {
        pending.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        let mut taken = 0;
        for &(s, e) in pending.iter() {
            if s > self.reach {
                break;
            }
            self.reach = self.reach.max(e);
            taken += 1;
        }
        pending.drain(..taken);
    }
}
