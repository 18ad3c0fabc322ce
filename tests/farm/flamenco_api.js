// SPDX-License-Identifier: GPL-3.0-or-later
// Flamenco Manager's job-compiler API as a job type sees it, written from Flamenco's
// documentation (Job Types; List of Commands) and its built-in job types: the globals
// `author` and `frameChunker`, and the job object compileJob(job) gets.
//   author.Task(name, type)        a task; both required. task.addCommand(command),
//                                  task.addDependency(otherTask).
//   author.Command(name, params)   a command: blender-render takes exe, exeArgs, argsBefore,
//                                  blendfile, args and runs {exe} {exeArgs} {argsBefore}
//                                  {blendfile} {args}.
//   frameChunker(frames, size)     frames such as "1-10,20" (or Blender's "1..10") in chunks
//                                  of at most `size` frames, each in regular notation where
//                                  runs of three or more frames are "a-b" and shorter ones
//                                  are listed ("1,2").
//   job.settings, job.addTask(task)
const author = {
    Task(name, type) {
        if (!String(name).trim() || !String(type).trim()) throw "author.Task(name, type): both are required";
        return {
            name: name, type: type, commands: [], dependencies: [],
            addCommand(command) { this.commands.push(command); },
            addDependency(task) { this.dependencies.push(task.name); },
        };
    },
    Command(name, parameters) { return { name: name, parameters: parameters }; },
};

function frameChunker(frames, chunkSize) {
    if (chunkSize < 1) throw `invalid chunk size ${chunkSize}`;
    const all = new Set();
    for (const part of String(frames).replace(/\.\./g, "-").split(",")) {
        const ends = part.split("-").map((s) => parseInt(s.trim(), 10));
        if (ends.some(isNaN) || ends.length > 2) throw `invalid range "${frames}"`;
        for (let f = ends[0]; f <= ends[ends.length - 1]; f++) all.add(f);
    }
    const sorted = [...all].sort((a, b) => a - b);
    const chunks = [];
    for (let i = 0; i < sorted.length; i += chunkSize) chunks.push(merge(sorted.slice(i, i + chunkSize)));
    return chunks;
}

function merge(frames) {
    const parts = [];
    let start = frames[0], previous = frames[0];
    const close = (from, to) => {
        if (from === to) parts.push(`${from}`);
        else if (from + 1 === to) parts.push(`${from}`, `${to}`);
        else parts.push(`${from}-${to}`);
    };
    for (const f of frames.slice(1)) {
        if (f > previous + 1) { close(start, previous); start = f; }
        previous = f;
    }
    close(start, previous);
    return parts.join(",");
}

function print() {}

// The job type's settings (JOB_TYPE) and the tasks compileJob authors for `settings`, as JSON.
function hyvoxCompile(settingsJson) {
    const job = { settings: JSON.parse(settingsJson), tasks: [], addTask(task) { this.tasks.push(task); } };
    compileJob(job);
    return JSON.stringify({ jobType: JOB_TYPE, tasks: job.tasks });
}

function hyvoxJobType() { return JSON.stringify(JOB_TYPE); }
