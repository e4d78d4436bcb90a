// A small link from the lab page to the tools page (graph, topics, rates, echo), opened in a new
// tab. It never takes keyboard focus (not tabbable, and a click does not focus it), so keys
// typed on this page keep going to the lab's keyboard and Enter never re-opens the link.
const CSS = `
  #teleop-nav-tools {
    position: fixed; left: 15px; top: 8px; z-index: 1000; padding: 3px 9px; border-radius: 6px;
    font: 12px/1.45 system-ui, sans-serif; text-decoration: none; white-space: nowrap;
    background: rgba(255, 255, 255, 0.85); color: #1f5fbf; box-shadow: 0 1px 4px rgba(0, 0, 0, 0.2);
  }
  #teleop-nav-tools:hover { text-decoration: underline; }
  [data-mantine-color-scheme="dark"] #teleop-nav-tools { background: rgba(30, 32, 36, 0.9); color: #8ab4f8; }
  @media (max-width: 820px) { #teleop-nav-tools { font-size: 11px; top: 6px; } }
`;

function addLink(): void {
  if (document.getElementById("teleop-nav-tools")) return;
  const style = document.createElement("style");
  style.textContent = CSS;
  const link = document.createElement("a");
  link.id = "teleop-nav-tools";
  link.href = "/tools";
  link.target = "_blank";
  link.rel = "noopener";
  link.tabIndex = -1;
  link.title = "Computation graph, node and topic info, rates and echo, in a new tab";
  link.textContent = "Graph & topics \u2197";
  link.addEventListener("mousedown", (e) => e.preventDefault());  // no focus on click
  link.addEventListener("click", () => link.blur());
  document.head.append(style);
  document.body.append(link);
}

/** Add the link once the page has a body. */
export function startNav(): void {
  if (document.body) addLink();
  else document.addEventListener("DOMContentLoaded", addLink);
}
