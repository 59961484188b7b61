//! [`Writer`]: a thread of its own that encodes a recording's messages and writes its files,
//! so that the platform's thread only hands over what it saw. Every wait on it is bounded: a
//! writer that stops keeping up (a full disk, a stalled file system) ends the run with an
//! error instead of blocking it, and nothing handed over is dropped.

use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, sync_channel};
use std::thread::JoinHandle;
use std::time::Duration;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;

use super::file::{McapFile, SimSample};
use crate::plugins::bounded_wait::{Refused, poll_within, send_within};

/// Jobs queued for the writer before the platform waits for it: at a state sample every 10
/// ticks, a second of a 500 Hz run.
const QUEUED_JOBS: usize = 64;

/// How long the writer may take no job before it is taken as stalled.
const STALL: Duration = Duration::from_secs(10);

/// How long the writer may take to write what is queued and close its files at the end.
const FINISH: Duration = Duration::from_secs(60);

/// What the writer does, in the order the platform saw it.
#[derive(Debug)]
pub(super) enum Job {
    /// Write into this episode's file until [`Job::EndEpisode`].
    BeginEpisode(Box<McapFile>),
    /// Close the episode's file, then say so (with the error, if it failed); write into the
    /// run's again.
    EndEpisode(SyncSender<Result<(), String>>),
    Log {
        time: f64,
        text: String,
    },
    State {
        time: f64,
        sim: Option<SimSample>,
    },
    Images {
        time: f64,
        images: Vec<ProbeImage>,
    },
}

/// See the [module](self).
#[derive(Debug)]
pub(super) struct Writer {
    jobs: Option<SyncSender<Job>>,
    thread: Option<JoinHandle<Result<(), BoxError>>>,
}

impl Writer {
    /// Starts the writer on `run`, the run's file.
    pub(super) fn start(run: McapFile) -> Result<Self, BoxError> {
        let (jobs, queue) = sync_channel(QUEUED_JOBS);
        let thread = std::thread::Builder::new()
            .name("mcap writer".to_owned())
            .spawn(move || write(run, &queue))
            .map_err(|e| format!("cannot start the recording's writer: {e}"))?;
        Ok(Self {
            jobs: Some(jobs),
            thread: Some(thread),
        })
    }

    /// Queues `job`, waiting at most [`STALL`] for room.
    ///
    /// # Errors
    ///
    /// When the writer failed (with its error) or stalled.
    pub(super) fn send(&mut self, job: Job) -> Result<(), BoxError> {
        let jobs = self.jobs.as_ref().ok_or("the recording has ended")?;
        match send_within(jobs, job, STALL) {
            Ok(()) => Ok(()),
            Err(Refused::Full) => {
                self.jobs = None;
                Err(format!(
                    "the recording's writer took nothing for {} s; the files are incomplete",
                    STALL.as_secs()
                )
                .into())
            }
            Err(Refused::Gone) => Err(self
                .finish()
                .err()
                .unwrap_or_else(|| "the recording's writer has ended".into())),
        }
    }

    /// Closes the episode's file, waiting (at most [`FINISH`]) until it is complete on disk, so
    /// that a behaviour, or a program beside the run, can read an episode's file once the
    /// episode has ended.
    ///
    /// # Errors
    ///
    /// The writer's, or when it does not close the file in time.
    pub(super) fn end_episode(&mut self) -> Result<(), BoxError> {
        let (closed, done) = sync_channel(1);
        self.send(Job::EndEpisode(closed))?;
        match done.recv_timeout(FINISH) {
            Ok(said) => said.map_err(BoxError::from),
            Err(RecvTimeoutError::Timeout) => Err(format!(
                "the recording's writer did not close the episode's file within {} s",
                FINISH.as_secs()
            )
            .into()),
            Err(RecvTimeoutError::Disconnected) => Err(self
                .finish()
                .err()
                .unwrap_or_else(|| "the recording's writer has ended".into())),
        }
    }

    /// Ends the queue and waits (at most [`FINISH`]) for the writer to write what is queued and
    /// close its files.
    ///
    /// # Errors
    ///
    /// The writer's, or when it does not finish in time.
    pub(super) fn finish(&mut self) -> Result<(), BoxError> {
        self.jobs = None;
        let Some(thread) = self.thread.take() else {
            return Ok(());
        };
        let finished = poll_within(FINISH, || Ok(thread.is_finished().then_some(())))?;
        if finished.is_none() {
            return Err(format!(
                "the recording's writer did not finish within {} s; the files are incomplete",
                FINISH.as_secs()
            )
            .into());
        }
        thread
            .join()
            .map_err(|_| BoxError::from("the recording's writer panicked"))?
    }
}

/// The writer's thread: does every job, then closes the files.
fn write(mut run: McapFile, queue: &Receiver<Job>) -> Result<(), BoxError> {
    let mut episode: Option<McapFile> = None;
    for job in queue {
        match job {
            Job::BeginEpisode(file) => episode = Some(*file),
            Job::EndEpisode(closed) => {
                let finished = episode.take().map_or(Ok(()), McapFile::finish);
                let said = finished.as_ref().map(|_| ()).map_err(ToString::to_string);
                let _platform_gave_up_waiting = closed.send(said);
                finished?;
            }
            Job::Log { time, text } => episode.as_mut().unwrap_or(&mut run).log(time, &text)?,
            Job::State { time, sim } => {
                episode
                    .as_mut()
                    .unwrap_or(&mut run)
                    .state(time, sim.as_ref())?;
            }
            Job::Images { time, images } => {
                episode.as_mut().unwrap_or(&mut run).images(time, &images)?;
            }
        }
    }
    if let Some(episode) = episode {
        episode.finish()?;
    }
    run.finish()
}
