// A list of callbacks that one failing callback cannot stop: each runs, and an error is logged.

export type Listeners<A extends unknown[]> = Array<(...args: A) => void>;

export function notify<A extends unknown[]>(listeners: Listeners<A>, ...args: A): void {
  for (const listener of listeners) {
    try { listener(...args); } catch (err) { console.error(err); }
  }
}
