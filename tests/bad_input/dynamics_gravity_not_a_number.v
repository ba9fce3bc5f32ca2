/* a component of the gravity that is not a number */
dynamics gravity: 0 down 0
