// swarf's worker under Node (worker_threads): worker.js, written for a Web Worker, sees the
// `self` it expects; messages that come before it is ready wait for it.
import { parentPort } from 'node:worker_threads';

const waiting = [];
globalThis.self = globalThis;
self.postMessage = (message, transfer) => parentPort.postMessage(message, transfer);
parentPort.on('message', (data) => (self.onmessage ? self.onmessage({ data }) : waiting.push(data)));
await import('./worker.js');
for (const data of waiting.splice(0)) self.onmessage({ data });
