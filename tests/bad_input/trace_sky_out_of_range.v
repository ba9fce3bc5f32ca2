/* a sky of negative radiance: no renderer may ignore it */
trace sky: 0.3,-1,0.3
