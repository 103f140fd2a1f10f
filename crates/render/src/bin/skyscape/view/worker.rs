//! The viewer's preparation thread: a scene whose time, sun, rung or settings changed is
//! prepared there (`Scene::prepare_in_stages` with one `PrepareCache` for the whole
//! run, so only what changed is built again) while the window keeps drawing the last
//! prepared scene and shows which stage is running.

use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::time::Instant;

use render::scene::{PrepareCache, PreparedScene, Scene};

/// What the thread reports.
pub(crate) enum Report {
    /// Request `generation` began the stage named.
    Stage(u64, &'static str),
    /// Request `generation` is prepared (or failed: the message), with each stage's
    /// wall time.
    Done {
        generation: u64,
        result: Box<Result<PreparedScene, String>>,
        stages: Vec<(&'static str, f64)>,
    },
}

/// A finished preparation: the scene (or why it failed) and each stage's wall time.
pub(crate) type Prepared = (Result<PreparedScene, String>, Vec<(&'static str, f64)>);

/// The thread and the last request sent to it.
pub(crate) struct Preparer {
    requests: Sender<(u64, Scene)>,
    reports: Receiver<Report>,
    /// The newest request sent.
    pub(crate) sent: u64,
    /// The newest request reported done.
    pub(crate) done: u64,
    /// The stage the newest request is in, while it runs.
    pub(crate) stage: Option<&'static str>,
}

impl Preparer {
    /// Starts the thread; it prepares for the GPU with `cache`.
    pub(crate) fn start(cache: PrepareCache) -> Self {
        let (requests, inbox) = channel::<(u64, Scene)>();
        let (outbox, reports) = channel();
        std::thread::Builder::new()
            .name("skyscape prepare".into())
            .spawn(move || run(&inbox, &outbox, &cache))
            .expect("spawning the preparation thread");
        Self {
            requests,
            reports,
            sent: 0,
            done: 0,
            stage: None,
        }
    }

    /// Asks for `scene` prepared; an older request still waiting is dropped.
    pub(crate) fn request(&mut self, scene: Scene) {
        self.sent += 1;
        // The thread only stops when this sender is dropped.
        let _ = self.requests.send((self.sent, scene));
    }

    /// Whether a request is still being prepared.
    pub(crate) fn busy(&self) -> bool {
        self.done < self.sent
    }

    /// The newest finished preparation since the last call, if any (older ones are
    /// skipped: a newer request supersedes them).
    pub(crate) fn poll(&mut self) -> Option<Prepared> {
        let mut newest = None;
        loop {
            match self.reports.try_recv() {
                Ok(Report::Stage(generation, name)) => {
                    if generation == self.sent {
                        self.stage = Some(name);
                    }
                }
                Ok(Report::Done {
                    generation,
                    result,
                    stages,
                }) => {
                    self.done = self.done.max(generation);
                    if generation == self.sent {
                        self.stage = None;
                    }
                    newest = Some((*result, stages));
                }
                Err(TryRecvError::Empty) => return newest,
                Err(TryRecvError::Disconnected) => {
                    self.done = self.sent;
                    return newest.or_else(|| {
                        Some((Err("the preparation thread stopped".into()), Vec::new()))
                    });
                }
            }
        }
    }
}

fn run(inbox: &Receiver<(u64, Scene)>, outbox: &Sender<Report>, cache: &PrepareCache) {
    while let Ok(mut request) = inbox.recv() {
        // Only the newest waiting request matters.
        while let Ok(newer) = inbox.try_recv() {
            request = newer;
        }
        let (generation, scene) = request;
        let mut stages: Vec<(&'static str, f64)> = Vec::new();
        let mut began = Instant::now();
        let result = scene.prepare_in_stages(true, cache, &mut |name| {
            if let Some(last) = stages.last_mut() {
                last.1 = began.elapsed().as_secs_f64();
            }
            began = Instant::now();
            stages.push((name, 0.0));
            let _ = outbox.send(Report::Stage(generation, name));
        });
        if let Some(last) = stages.last_mut() {
            last.1 = began.elapsed().as_secs_f64();
        }
        let report = Report::Done {
            generation,
            result: Box::new(result.map_err(|e| e.to_string())),
            stages,
        };
        if outbox.send(report).is_err() {
            return;
        }
    }
}
