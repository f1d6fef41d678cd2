//! What a run of a planner is estimated to allocate, so that a run that would not fit is
//! refused before anything large is allocated. Each planner estimates its own state; the
//! experiment layer adds what every run holds and checks the sum against the limit.

/// What a run is estimated to need, and the key that drives it (named when it is refused).
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryEstimate {
    /// Bytes, an upper estimate.
    pub bytes: f64,
    /// The experiment-file key that mostly decides the size.
    pub key: &'static str,
    /// What is being allocated, in words (`1000 individuals of up to 200 actions`).
    pub what: String,
}

/// Bytes of a set of `cells` bits stored as 64-bit words.
pub fn bitset_bytes(cells: f64) -> f64 {
    8.0 * (cells / 64.0).ceil()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_sets_round_up_to_whole_words() {
        for (cells, bytes) in [(0.0, 0.0), (1.0, 8.0), (64.0, 8.0), (65.0, 16.0), (6400.0, 800.0)] {
            assert_eq!(bitset_bytes(cells), bytes, "{cells} cells");
        }
    }
}
