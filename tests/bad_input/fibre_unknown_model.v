/* a fibre: line naming no model */
fibre: hairs 1 marschner
