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
use crate::plugins::bounded_wait::{Refused, send_within};

/// Jobs handed over together: waking the writer costs the platform's thread more than a job.
const BATCH: usize = 32;

/// Batches queued for the writer before the platform waits for it: at a state sample every 10
/// ticks, a second of a 500 Hz run.
const QUEUED_BATCHES: usize = 2;

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
        states: Vec<serde_json::Value>,
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
    pending: Vec<Job>,
    jobs: Option<SyncSender<Vec<Job>>>,
    thread: Option<JoinHandle<()>>,
    /// What the thread ended with, said as it ends.
    ended: Receiver<Result<(), String>>,
}

impl Writer {
    /// Starts the writer on `run`, the run's file.
    pub(super) fn start(run: McapFile) -> Result<Self, BoxError> {
        let (jobs, queue) = sync_channel(QUEUED_BATCHES);
        let (said, ended) = sync_channel(1);
        let thread = std::thread::Builder::new()
            .name("mcap writer".to_owned())
            .spawn(move || {
                let result = write(run, &queue).map_err(|e| e.to_string());
                let _nobody_waits_any_more = said.send(result);
            })
            .map_err(|e| format!("cannot start the recording's writer: {e}"))?;
        Ok(Self {
            pending: Vec::with_capacity(BATCH),
            jobs: Some(jobs),
            thread: Some(thread),
            ended,
        })
    }

    /// Queues `job`, handing the queue over once it holds a batch, waiting at most [`STALL`]
    /// for room.
    ///
    /// # Errors
    ///
    /// When the writer failed (with its error) or stalled.
    pub(super) fn send(&mut self, job: Job) -> Result<(), BoxError> {
        let waited_for = matches!(job, Job::EndEpisode(_));
        self.pending.push(job);
        if waited_for || self.pending.len() >= BATCH {
            self.hand_over()?;
        }
        Ok(())
    }

    fn hand_over(&mut self) -> Result<(), BoxError> {
        let jobs = self.jobs.as_ref().ok_or("the recording has ended")?;
        let batch = std::mem::replace(&mut self.pending, Vec::with_capacity(BATCH));
        let refused = match send_within(jobs, batch, STALL) {
            Ok(()) => return Ok(()),
            Err(refused) => refused,
        };
        self.jobs = None;
        Err(match refused {
            Refused::Full => format!(
                "the recording's writer took nothing for {} s; the files are incomplete",
                STALL.as_secs()
            )
            .into(),
            Refused::Gone => self.why_it_ended(),
        })
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
            Err(RecvTimeoutError::Disconnected) => Err(self.why_it_ended()),
        }
    }

    /// Why the writer, found gone, ended: its error.
    fn why_it_ended(&mut self) -> BoxError {
        self.finish()
            .err()
            .unwrap_or_else(|| "the recording's writer has ended".into())
    }

    /// Ends the queue and waits (at most [`FINISH`]) for the writer to write what is queued and
    /// close its files.
    ///
    /// # Errors
    ///
    /// The writer's, or when it does not finish in time.
    pub(super) fn finish(&mut self) -> Result<(), BoxError> {
        let handed_over = if self.jobs.is_some() {
            self.hand_over()
        } else {
            Ok(())
        };
        self.jobs = None;
        let Some(thread) = self.thread.take() else {
            return handed_over;
        };
        let result = match self.ended.recv_timeout(FINISH) {
            Ok(result) => result.map_err(BoxError::from),
            Err(RecvTimeoutError::Timeout) => {
                return Err(format!(
                    "the recording's writer did not finish within {} s; the files are incomplete",
                    FINISH.as_secs()
                )
                .into());
            }
            Err(RecvTimeoutError::Disconnected) => Err("the recording's writer panicked".into()),
        };
        let _ended_already = thread.join();
        handed_over.and(result)
    }
}

/// The writer's thread: does every job, then closes the files.
fn write(mut run: McapFile, queue: &Receiver<Vec<Job>>) -> Result<(), BoxError> {
    let mut episode: Option<McapFile> = None;
    for job in queue.iter().flatten() {
        match job {
            Job::BeginEpisode(file) => episode = Some(*file),
            Job::EndEpisode(closed) => {
                let finished = episode.take().map_or(Ok(()), McapFile::finish);
                let said = finished.as_ref().map(|_| ()).map_err(ToString::to_string);
                let _platform_gave_up_waiting = closed.send(said);
                finished?;
            }
            Job::Log { time, text } => episode.as_mut().unwrap_or(&mut run).log(time, &text)?,
            Job::State { time, states, sim } => {
                episode
                    .as_mut()
                    .unwrap_or(&mut run)
                    .state(time, &states, sim.as_ref())?;
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
