//! Episodes: numbered parts of a run that each start from the world's start state, so that a
//! run's episodes — and their recordings — are the same whichever others ran before them.

use super::LogLine;
use crate::BoxError;

/// An episode: its number (the behaviour's, e.g. the index of a press in a grid) and the tick
/// it began on ([`Pl::begin_episode`](super::Pl::begin_episode)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Episode {
    /// The behaviour's number for it.
    pub number: u64,
    /// The platform's tick count when it began.
    pub start_tick: u64,
}

impl Episode {
    /// Seconds since the episode began at platform tick `tick`, counted in whole ticks, so
    /// that the same moment of an episode reads the same time in every run, whatever platform
    /// time the episode began at.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::runtime::Episode;
    ///
    /// let episode = Episode { number: 7, start_tick: 1_000 };
    /// assert_eq!(episode.time_at(1_250, 0.002), 0.5);
    /// ```
    pub fn time_at(&self, tick: u64, timestep: f64) -> f64 {
        tick.saturating_sub(self.start_tick) as f64 * timestep
    }
}

/// What a behaviour did that plugins see, in the order it happened
/// ([`World::happenings`](super::World::happenings)): a line it logged, an episode it began or
/// ended, the task it set.
#[derive(Debug, Clone, PartialEq)]
pub enum Happening {
    /// A line logged with [`Pl::log`](super::Pl::log).
    Logged(LogLine),
    /// An episode began ([`Pl::begin_episode`](super::Pl::begin_episode)).
    EpisodeBegan(Episode),
    /// An episode ended ([`Pl::end_episode`](super::Pl::end_episode), or the next one began).
    EpisodeEnded(Episode),
    /// The behaviour said what it is doing from now on ([`Pl::set_task`](super::Pl::set_task)).
    TaskSet(String),
}

/// Why an episode could not begin.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EpisodeError {
    /// The world cannot go back to its start state.
    #[error("episode {number} cannot begin: the world cannot go back to its start state: {source}")]
    Restart {
        /// The episode's number.
        number: u64,
        /// What the backend said.
        #[source]
        source: BoxError,
    },
    /// The number was begun before in this run: its recordings would be overwritten.
    #[error(
        "episode {number} was already begun in this run: its recordings would be overwritten \
         (number each episode once)"
    )]
    Repeated {
        /// The episode's number.
        number: u64,
    },
}
