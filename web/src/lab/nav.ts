// A small link from the lab page to the tools page (graph, topics, rates, echo), opened in a new
// tab, in the workbench's toolbar (workbench.ts moves it there). It never takes keyboard focus (not tabbable, and a click does not focus it), so keys
// typed on this page keep going to the lab's keyboard and Enter never re-opens the link.
const CSS = `
  #teleop-nav-tools {
    padding: 3px 9px; border-radius: 6px;
    font: 12px/1.45 system-ui, sans-serif; text-decoration: none; white-space: nowrap; color: #1f5fbf;
  }
  #teleop-nav-tools:hover { text-decoration: underline; }
  [data-mantine-color-scheme="dark"] #teleop-nav-tools { color: #8ab4f8; }
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
