/* shells need at least one layer */
fur layers: 0
