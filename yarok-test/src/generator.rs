//! A small deterministic generator (xorshift64*) for the parsers' generated-input tests: the
//! same seed gives the same inputs on every machine.

/// The generator; its `u64` is the state (the seed, which must not be 0).
#[derive(Debug, Clone)]
pub struct Generator(pub u64);

impl Generator {
    /// The next number.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number below `n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// One of `from`.
    pub fn pick<'a>(&mut self, from: &[&'a str]) -> &'a str {
        from[self.below(from.len())]
    }

    /// `n` bytes.
    pub fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.next_u64() as u8).collect()
    }
}

/// How many generated inputs a fuzz test tries: `YAROK_FUZZ_INPUTS`, or 100 000.
pub fn fuzz_inputs() -> usize {
    std::env::var("YAROK_FUZZ_INPUTS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(100_000)
}
