// The scene picker: one button per usable scene of the catalogue, showing the thumbnail
// prt-serve lists for it (/api/scenes "thumbnail": a 160x120 PNG with a transparent
// background, docs/server.md) or, for a scene without one or whose image fails to load, a
// placeholder with the scene's initial. Plain buttons, so the keyboard works as everywhere:
// Tab reaches them, Enter or Space picks one; the arrow keys also move between them. The
// scene shown is marked aria-pressed (and outlined).
export class ScenePicker {
  // Fills `container` (emptied first) with the scenes' buttons; `onPick(name)` is called
  // when one is chosen (the caller loads the scene and then calls select(name)).
  constructor(container, scenes, onPick) {
    this.buttons = new Map();
    container.replaceChildren();
    container.classList.add('scene-picker');
    container.setAttribute('role', 'group');
    container.setAttribute('aria-label', 'Scenes');
    for (const scene of scenes) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'scene-tile';
      button.dataset.scene = scene.name;
      button.title = `${scene.name}: ${scene.vertices} vertices, SH order ${scene.shOrder}`;
      button.setAttribute('aria-pressed', 'false');
      const picture = document.createElement('span');
      picture.className = 'scene-picture';
      if (scene.thumbnail) {
        const img = document.createElement('img');
        img.src = scene.thumbnail;
        img.alt = '';  // the label below names the scene
        img.width = 160;
        img.height = 120;
        img.decoding = 'async';
        img.addEventListener('error', () => picture.replaceChildren(placeholder(scene.name)));
        picture.append(img);
      } else {
        picture.append(placeholder(scene.name));
      }
      const label = document.createElement('span');
      label.className = 'scene-label';
      label.textContent = scene.name;
      button.append(picture, label);
      button.addEventListener('click', () => onPick(scene.name));
      button.addEventListener('keydown', (e) => this.moveFocus(e, button));
      container.append(button);
      this.buttons.set(scene.name, button);
    }
  }

  // Marks `name` as the scene shown.
  select(name) {
    for (const [n, b] of this.buttons) b.setAttribute('aria-pressed', String(n === name));
  }

  moveFocus(e, button) {
    const step = { ArrowRight: 1, ArrowDown: 1, ArrowLeft: -1, ArrowUp: -1 }[e.key];
    if (!step) return;
    const all = [...this.buttons.values()];
    const next = all[(all.indexOf(button) + step + all.length) % all.length];
    next.focus();
    e.preventDefault();
  }
}

function placeholder(name) {
  const span = document.createElement('span');
  span.className = 'scene-placeholder';
  span.setAttribute('aria-hidden', 'true');
  span.textContent = (name.trim()[0] || '?').toUpperCase();
  return span;
}
