//! Sharing the frames of an animation among machines: share K of N (K counts from 1) renders
//! the frames i with i mod N = K − 1. Round-robin rather than blocks, so that every share gets
//! early and late frames alike when their cost changes over the flight.

use anyhow::bail;

use crate::cli::ShardArg;

/// One share of an animation's frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, 1 to `count`.
    index: u32,
    /// N, at least 1.
    count: u32,
}

impl Shard {
    /// All frames: share 1 of 1.
    pub const WHOLE: Self = Self { index: 1, count: 1 };

    /// Share K of N as given by `--shard K/N`.
    ///
    /// # Errors
    /// If N is 0 or K is not between 1 and N; the message names the option.
    pub fn new(arg: ShardArg) -> anyhow::Result<Self> {
        let ShardArg { index, count } = arg;
        if count == 0 {
            bail!("--shard {index}/{count}: N, the number of shares, must be at least 1");
        }
        if index == 0 || index > count {
            bail!("--shard {index}/{count}: K must be between 1 and {count} (shares count from 1)");
        }
        Ok(Self { index, count })
    }

    /// K, the share (from 1).
    pub const fn index(self) -> u32 {
        self.index
    }

    /// N, the number of shares.
    pub const fn count(self) -> u32 {
        self.count
    }

    /// The frames of `0..total` this share renders, in order.
    pub fn frames(self, total: u32) -> impl Iterator<Item = u32> {
        (self.index - 1..total).step_by(self.count as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::Shard;
    use crate::cli::ShardArg;

    fn shard(index: u32, count: u32) -> anyhow::Result<Shard> {
        Shard::new(ShardArg { index, count })
    }

    /// Every frame belongs to exactly one share, whatever the number of shares and frames.
    #[test]
    fn shares_partition_the_frames() {
        for count in 1..=7 {
            for total in 0..=20 {
                let mut owner = vec![0_u32; total as usize];
                for index in 1..=count {
                    for frame in shard(index, count).unwrap().frames(total) {
                        assert_eq!(frame % count, index - 1);
                        owner[frame as usize] += 1;
                    }
                }
                assert!(
                    owner.iter().all(|&n| n == 1),
                    "{count} shares of {total}: {owner:?}"
                );
            }
        }
        assert_eq!(Shard::WHOLE.frames(3).collect::<Vec<_>>(), [0, 1, 2]);
    }

    /// K outside 1..=N and N = 0 are refused, naming the option.
    #[test]
    fn out_of_range_shares_are_refused() {
        for (index, count) in [(3, 2), (0, 0), (0, 3), (1, 0)] {
            let message = shard(index, count).unwrap_err().to_string();
            assert!(
                message.starts_with(&format!("--shard {index}/{count}")),
                "{message}"
            );
        }
    }
}
