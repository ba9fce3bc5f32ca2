/* stems may not come nearer than the minimum separation, which repulsion's thickness must
   exceed */
dynamics thickness: 0.01 0.05
